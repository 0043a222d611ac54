(unstack d c)
(put-down d)
(pick-up c)
(stack c a)

(define (problem BW-generalization-4)
(:domain blocksworld-4ops)(:objects a b c d)
(:init
(arm-empty)
(clear a)
(clear d)
(on a b)
(on d c)
(on-table b)
(on-table c)
)
(:goal
(and
(on c a))
)
)

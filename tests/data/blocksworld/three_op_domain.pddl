; the 3-operator move domain
(define (domain blocksworld-3ops)
  (:requirements :strips :equality)
  (:predicates (clear ?x) (on-table ?x) (on ?x ?y))
  (:action move-b-to-b
    :parameters (?bm ?bf ?bt)
    :precondition (and (clear ?bm) (clear ?bt) (on ?bm ?bf) (not (= ?bm ?bt)))
    :effect (and (not (clear ?bt)) (not (on ?bm ?bf)) (on ?bm ?bt) (clear ?bf)))
  (:action move-b-to-t
    :parameters (?bm ?bf)
    :precondition (and (clear ?bm) (on ?bm ?bf))
    :effect (and (not (on ?bm ?bf)) (on-table ?bm) (clear ?bf)))
  (:action move-t-to-b
    :parameters (?bm ?bt)
    :precondition (and (clear ?bm) (clear ?bt) (on-table ?bm) (not (= ?bm ?bt)))
    :effect (and (not (clear ?bt)) (not (on-table ?bm)) (on ?bm ?bt))))

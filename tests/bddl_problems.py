"""BEHAVIOR-1K problems the importer tests share: a small activity in BDDL, and the same
with a predicate VeriGraph does not support."""

DISHES = """(define (problem putting_dishes_away-0)
    (:domain omnigibson)
    (:objects
        plate.n.04_1 plate.n.04_2 - plate.n.04
        countertop.n.01_1 - countertop.n.01
        cabinet.n.01_1 cabinet.n.01_* - cabinet.n.01
        electric_refrigerator.n.01_1 - electric_refrigerator.n.01
        floor.n.01_1 - floor.n.01
        agent.n.01_1 - agent.n.01
    )
    (:init
        (ontop plate.n.04_1 countertop.n.01_1)
        (ontop plate.n.04_2 countertop.n.01_1)
        (inroom countertop.n.01_1 kitchen)
        (inroom cabinet.n.01_1 kitchen)
        (inroom cabinet.n.01_* kitchen)
        (inroom electric_refrigerator.n.01_1 kitchen)
        (open electric_refrigerator.n.01_1)
        (inroom floor.n.01_1 kitchen)
        (ontop agent.n.01_1 floor.n.01_1)
    )
    (:goal
        (and
            (forall (?plate.n.04 - plate.n.04) (inside ?plate.n.04 ?cabinet.n.01_1))
            (not (open ?electric_refrigerator.n.01_1))
        )
    )
)"""

FILLED = DISHES.replace("(open electric_refrigerator.n.01_1)",
                        "(filled electric_refrigerator.n.01_1 water.n.06_1)")

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

# Two bottles in the cabinet, next to each other (BEHAVIOR's store_vodka): `nextto`
# beside `inside`, which one placement per object reaches by putting the second bottle
# next to the first (it stands where the first stands).
VODKA = """(define (problem store_vodka-0)
    (:domain omnigibson)
    (:objects
        bottle__of__vodka.n.01_1 bottle__of__vodka.n.01_2 - bottle__of__vodka.n.01
        cabinet.n.01_1 - cabinet.n.01
        floor.n.01_1 - floor.n.01
        agent.n.01_1 - agent.n.01
    )
    (:init
        (ontop bottle__of__vodka.n.01_1 floor.n.01_1)
        (ontop bottle__of__vodka.n.01_2 floor.n.01_1)
        (inroom cabinet.n.01_1 kitchen)
        (inroom floor.n.01_1 kitchen)
        (ontop agent.n.01_1 floor.n.01_1)
    )
    (:goal
        (and
            (forall (?bottle__of__vodka.n.01 - bottle__of__vodka.n.01)
                (inside ?bottle__of__vodka.n.01 ?cabinet.n.01_1))
            (nextto ?bottle__of__vodka.n.01_1 ?bottle__of__vodka.n.01_2)
        )
    )
)"""

# Firewood on the living room's floor next to the fireplace (BEHAVIOR's
# bringing_in_kindling): next to furniture is on the floor of its room.
KINDLING = """(define (problem bringing_in_kindling-0)
    (:domain omnigibson)
    (:objects
        firewood.n.01_1 firewood.n.01_2 - firewood.n.01
        driveway.n.01_1 - driveway.n.01
        wood_fireplace.n.01_1 - wood_fireplace.n.01
        floor.n.01_1 floor.n.01_2 - floor.n.01
        agent.n.01_1 - agent.n.01
    )
    (:init
        (ontop firewood.n.01_1 driveway.n.01_1)
        (ontop firewood.n.01_2 driveway.n.01_1)
        (inroom driveway.n.01_1 garden)
        (inroom floor.n.01_1 garden)
        (inroom floor.n.01_2 living_room)
        (inroom wood_fireplace.n.01_1 living_room)
        (ontop agent.n.01_1 floor.n.01_1)
    )
    (:goal
        (and
            (forall (?firewood.n.01 - firewood.n.01)
                (and (ontop ?firewood.n.01 ?floor.n.01_2)
                     (nextto ?firewood.n.01 ?wood_fireplace.n.01_1)))
        )
    )
)"""

# Fruit to cook and nothing that heats (BEHAVIOR's make_stewed_fruit lists no stove).
STEWED = """(define (problem make_stewed_fruit-0)
    (:domain omnigibson)
    (:objects
        pear.n.01_1 - pear.n.01
        bowl.n.01_1 - bowl.n.01
        countertop.n.01_1 - countertop.n.01
        floor.n.01_1 - floor.n.01
        agent.n.01_1 - agent.n.01
    )
    (:init
        (ontop pear.n.01_1 countertop.n.01_1)
        (not (cooked pear.n.01_1))
        (ontop bowl.n.01_1 countertop.n.01_1)
        (inroom countertop.n.01_1 kitchen)
        (inroom floor.n.01_1 kitchen)
        (ontop agent.n.01_1 floor.n.01_1)
    )
    (:goal (and (cooked ?pear.n.01_1)))
)"""

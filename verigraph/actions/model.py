"""Actions an agent proposes: `move` (tabletop), the state changes `open`, `close`,
`toggle_on`, `toggle_off` (household), `align` (tangram) and the end token `done`.

What each action requires and does is its row in `verigraph.actions.schemas`."""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import BaseModel, ConfigDict, Field, TypeAdapter

NAME = Field(min_length=1, max_length=128)


class MoveAction(BaseModel):
    """`move(object, relation, target)`: put object on or in target."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    action: Literal["move"] = "move"
    object: str = Field(min_length=1, max_length=128, description="id of the object to move")
    relation: str = Field(default="on", min_length=1, max_length=32,
                          description="on, in, under, nextto")
    target: str = Field(min_length=1, max_length=128, description="id of the new support")

    def text(self) -> str:
        return f"move({self.object}, {self.relation}, {self.target})"


StateActionName = Literal["open", "close", "toggle_on", "toggle_off"]


class StateAction(BaseModel):
    """`open(x)`, `close(x)`, `toggle_on(x)`, `toggle_off(x)`: change one state of x."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    action: StateActionName
    object: str = Field(min_length=1, max_length=128,
                        description="id of an openable (open, close) or toggleable object")

    def text(self) -> str:
        return f"{self.action}({self.object})"


class AlignAction(BaseModel):
    """`align(piece, side, target, target_side)`: put a side of a piece against another's."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    action: Literal["align"] = "align"
    object: str = Field(min_length=1, max_length=128, description="tangram piece to move")
    side: int = Field(description="moved piece's side, clockwise from the right angle "
                                  "(acute vertex)")
    target: str = Field(min_length=1, max_length=128, description="piece that stays")
    target_side: int = Field(description="side index on the target piece")

    def text(self) -> str:
        return f"align({self.object}, {self.side}, {self.target}, {self.target_side})"


class DoneAction(BaseModel):
    """The end token: the planner believes the goal is reached."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    action: Literal["done"] = "done"

    def text(self) -> str:
        return "done"


Action = Annotated[MoveAction | StateAction | AlignAction | DoneAction,
                   Field(discriminator="action")]
ActionAdapter: TypeAdapter[MoveAction | StateAction | AlignAction | DoneAction] = \
    TypeAdapter(Action)
ActionListAdapter: TypeAdapter[list[MoveAction | StateAction | AlignAction | DoneAction]] = \
    TypeAdapter(list[Action])

AnyAction = MoveAction | StateAction | AlignAction | DoneAction

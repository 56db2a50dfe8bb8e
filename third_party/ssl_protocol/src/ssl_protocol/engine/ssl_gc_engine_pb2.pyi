import datetime

from ssl_protocol.geom import ssl_gc_geometry_pb2 as _ssl_gc_geometry_pb2
from ssl_protocol.state import ssl_gc_common_pb2 as _ssl_gc_common_pb2
from google.protobuf import timestamp_pb2 as _timestamp_pb2
from google.protobuf.internal import containers as _containers
from google.protobuf.internal import enum_type_wrapper as _enum_type_wrapper
from google.protobuf import descriptor as _descriptor
from google.protobuf import message as _message
from collections.abc import Iterable as _Iterable, Mapping as _Mapping
from typing import ClassVar as _ClassVar, Optional as _Optional, Union as _Union

DESCRIPTOR: _descriptor.FileDescriptor

class GcState(_message.Message):
    __slots__ = ("team_state", "auto_ref_state", "trackers", "continue_actions", "continue_hints")
    class TeamStateEntry(_message.Message):
        __slots__ = ("key", "value")
        KEY_FIELD_NUMBER: _ClassVar[int]
        VALUE_FIELD_NUMBER: _ClassVar[int]
        key: str
        value: GcStateTeam
        def __init__(self, key: _Optional[str] = ..., value: _Optional[_Union[GcStateTeam, _Mapping]] = ...) -> None: ...
    class AutoRefStateEntry(_message.Message):
        __slots__ = ("key", "value")
        KEY_FIELD_NUMBER: _ClassVar[int]
        VALUE_FIELD_NUMBER: _ClassVar[int]
        key: str
        value: GcStateAutoRef
        def __init__(self, key: _Optional[str] = ..., value: _Optional[_Union[GcStateAutoRef, _Mapping]] = ...) -> None: ...
    class TrackersEntry(_message.Message):
        __slots__ = ("key", "value")
        KEY_FIELD_NUMBER: _ClassVar[int]
        VALUE_FIELD_NUMBER: _ClassVar[int]
        key: str
        value: str
        def __init__(self, key: _Optional[str] = ..., value: _Optional[str] = ...) -> None: ...
    TEAM_STATE_FIELD_NUMBER: _ClassVar[int]
    AUTO_REF_STATE_FIELD_NUMBER: _ClassVar[int]
    TRACKERS_FIELD_NUMBER: _ClassVar[int]
    CONTINUE_ACTIONS_FIELD_NUMBER: _ClassVar[int]
    CONTINUE_HINTS_FIELD_NUMBER: _ClassVar[int]
    team_state: _containers.MessageMap[str, GcStateTeam]
    auto_ref_state: _containers.MessageMap[str, GcStateAutoRef]
    trackers: _containers.ScalarMap[str, str]
    continue_actions: _containers.RepeatedCompositeFieldContainer[ContinueAction]
    continue_hints: _containers.RepeatedCompositeFieldContainer[ContinueHint]
    def __init__(self, team_state: _Optional[_Mapping[str, GcStateTeam]] = ..., auto_ref_state: _Optional[_Mapping[str, GcStateAutoRef]] = ..., trackers: _Optional[_Mapping[str, str]] = ..., continue_actions: _Optional[_Iterable[_Union[ContinueAction, _Mapping]]] = ..., continue_hints: _Optional[_Iterable[_Union[ContinueHint, _Mapping]]] = ...) -> None: ...

class GcStateTeam(_message.Message):
    __slots__ = ("connected", "connection_verified", "remote_control_connected", "remote_control_connection_verified", "advantage_choice")
    CONNECTED_FIELD_NUMBER: _ClassVar[int]
    CONNECTION_VERIFIED_FIELD_NUMBER: _ClassVar[int]
    REMOTE_CONTROL_CONNECTED_FIELD_NUMBER: _ClassVar[int]
    REMOTE_CONTROL_CONNECTION_VERIFIED_FIELD_NUMBER: _ClassVar[int]
    ADVANTAGE_CHOICE_FIELD_NUMBER: _ClassVar[int]
    connected: bool
    connection_verified: bool
    remote_control_connected: bool
    remote_control_connection_verified: bool
    advantage_choice: TeamAdvantageChoice
    def __init__(self, connected: _Optional[bool] = ..., connection_verified: _Optional[bool] = ..., remote_control_connected: _Optional[bool] = ..., remote_control_connection_verified: _Optional[bool] = ..., advantage_choice: _Optional[_Union[TeamAdvantageChoice, _Mapping]] = ...) -> None: ...

class TeamAdvantageChoice(_message.Message):
    __slots__ = ("choice",)
    class AdvantageChoice(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
        __slots__ = ()
        STOP: _ClassVar[TeamAdvantageChoice.AdvantageChoice]
        CONTINUE: _ClassVar[TeamAdvantageChoice.AdvantageChoice]
    STOP: TeamAdvantageChoice.AdvantageChoice
    CONTINUE: TeamAdvantageChoice.AdvantageChoice
    CHOICE_FIELD_NUMBER: _ClassVar[int]
    choice: TeamAdvantageChoice.AdvantageChoice
    def __init__(self, choice: _Optional[_Union[TeamAdvantageChoice.AdvantageChoice, str]] = ...) -> None: ...

class GcStateAutoRef(_message.Message):
    __slots__ = ("connection_verified",)
    CONNECTION_VERIFIED_FIELD_NUMBER: _ClassVar[int]
    connection_verified: bool
    def __init__(self, connection_verified: _Optional[bool] = ...) -> None: ...

class GcStateTracker(_message.Message):
    __slots__ = ("source_name", "uuid", "ball", "robots")
    SOURCE_NAME_FIELD_NUMBER: _ClassVar[int]
    UUID_FIELD_NUMBER: _ClassVar[int]
    BALL_FIELD_NUMBER: _ClassVar[int]
    ROBOTS_FIELD_NUMBER: _ClassVar[int]
    source_name: str
    uuid: str
    ball: Ball
    robots: _containers.RepeatedCompositeFieldContainer[Robot]
    def __init__(self, source_name: _Optional[str] = ..., uuid: _Optional[str] = ..., ball: _Optional[_Union[Ball, _Mapping]] = ..., robots: _Optional[_Iterable[_Union[Robot, _Mapping]]] = ...) -> None: ...

class Ball(_message.Message):
    __slots__ = ("pos", "vel")
    POS_FIELD_NUMBER: _ClassVar[int]
    VEL_FIELD_NUMBER: _ClassVar[int]
    pos: _ssl_gc_geometry_pb2.Vector3
    vel: _ssl_gc_geometry_pb2.Vector3
    def __init__(self, pos: _Optional[_Union[_ssl_gc_geometry_pb2.Vector3, _Mapping]] = ..., vel: _Optional[_Union[_ssl_gc_geometry_pb2.Vector3, _Mapping]] = ...) -> None: ...

class Robot(_message.Message):
    __slots__ = ("id", "pos")
    ID_FIELD_NUMBER: _ClassVar[int]
    POS_FIELD_NUMBER: _ClassVar[int]
    id: _ssl_gc_common_pb2.RobotId
    pos: _ssl_gc_geometry_pb2.Vector2
    def __init__(self, id: _Optional[_Union[_ssl_gc_common_pb2.RobotId, _Mapping]] = ..., pos: _Optional[_Union[_ssl_gc_geometry_pb2.Vector2, _Mapping]] = ...) -> None: ...

class ContinueAction(_message.Message):
    __slots__ = ("type", "for_team", "continuation_issues", "ready_at", "state")
    class Type(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
        __slots__ = ()
        TYPE_UNKNOWN: _ClassVar[ContinueAction.Type]
        HALT: _ClassVar[ContinueAction.Type]
        RESUME_FROM_HALT: _ClassVar[ContinueAction.Type]
        STOP_GAME: _ClassVar[ContinueAction.Type]
        FORCE_START: _ClassVar[ContinueAction.Type]
        FREE_KICK: _ClassVar[ContinueAction.Type]
        NEXT_COMMAND: _ClassVar[ContinueAction.Type]
        BALL_PLACEMENT_START: _ClassVar[ContinueAction.Type]
        BALL_PLACEMENT_CANCEL: _ClassVar[ContinueAction.Type]
        BALL_PLACEMENT_COMPLETE: _ClassVar[ContinueAction.Type]
        BALL_PLACEMENT_FAIL: _ClassVar[ContinueAction.Type]
        TIMEOUT_START: _ClassVar[ContinueAction.Type]
        TIMEOUT_STOP: _ClassVar[ContinueAction.Type]
        BOT_SUBSTITUTION: _ClassVar[ContinueAction.Type]
        NEXT_STAGE: _ClassVar[ContinueAction.Type]
        END_GAME: _ClassVar[ContinueAction.Type]
        ACCEPT_GOAL: _ClassVar[ContinueAction.Type]
        REJECT_GOAL: _ClassVar[ContinueAction.Type]
        NORMAL_START: _ClassVar[ContinueAction.Type]
        CHALLENGE_ACCEPT: _ClassVar[ContinueAction.Type]
        CHALLENGE_REJECT: _ClassVar[ContinueAction.Type]
        CORRECT_BALL_LEFT_FIELD_TEAM: _ClassVar[ContinueAction.Type]
    TYPE_UNKNOWN: ContinueAction.Type
    HALT: ContinueAction.Type
    RESUME_FROM_HALT: ContinueAction.Type
    STOP_GAME: ContinueAction.Type
    FORCE_START: ContinueAction.Type
    FREE_KICK: ContinueAction.Type
    NEXT_COMMAND: ContinueAction.Type
    BALL_PLACEMENT_START: ContinueAction.Type
    BALL_PLACEMENT_CANCEL: ContinueAction.Type
    BALL_PLACEMENT_COMPLETE: ContinueAction.Type
    BALL_PLACEMENT_FAIL: ContinueAction.Type
    TIMEOUT_START: ContinueAction.Type
    TIMEOUT_STOP: ContinueAction.Type
    BOT_SUBSTITUTION: ContinueAction.Type
    NEXT_STAGE: ContinueAction.Type
    END_GAME: ContinueAction.Type
    ACCEPT_GOAL: ContinueAction.Type
    REJECT_GOAL: ContinueAction.Type
    NORMAL_START: ContinueAction.Type
    CHALLENGE_ACCEPT: ContinueAction.Type
    CHALLENGE_REJECT: ContinueAction.Type
    CORRECT_BALL_LEFT_FIELD_TEAM: ContinueAction.Type
    class State(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
        __slots__ = ()
        STATE_UNKNOWN: _ClassVar[ContinueAction.State]
        BLOCKED: _ClassVar[ContinueAction.State]
        WAITING: _ClassVar[ContinueAction.State]
        READY_AUTO: _ClassVar[ContinueAction.State]
        READY_MANUAL: _ClassVar[ContinueAction.State]
        DISABLED: _ClassVar[ContinueAction.State]
    STATE_UNKNOWN: ContinueAction.State
    BLOCKED: ContinueAction.State
    WAITING: ContinueAction.State
    READY_AUTO: ContinueAction.State
    READY_MANUAL: ContinueAction.State
    DISABLED: ContinueAction.State
    TYPE_FIELD_NUMBER: _ClassVar[int]
    FOR_TEAM_FIELD_NUMBER: _ClassVar[int]
    CONTINUATION_ISSUES_FIELD_NUMBER: _ClassVar[int]
    READY_AT_FIELD_NUMBER: _ClassVar[int]
    STATE_FIELD_NUMBER: _ClassVar[int]
    type: ContinueAction.Type
    for_team: _ssl_gc_common_pb2.Team
    continuation_issues: _containers.RepeatedScalarFieldContainer[str]
    ready_at: _timestamp_pb2.Timestamp
    state: ContinueAction.State
    def __init__(self, type: _Optional[_Union[ContinueAction.Type, str]] = ..., for_team: _Optional[_Union[_ssl_gc_common_pb2.Team, str]] = ..., continuation_issues: _Optional[_Iterable[str]] = ..., ready_at: _Optional[_Union[datetime.datetime, _timestamp_pb2.Timestamp, _Mapping]] = ..., state: _Optional[_Union[ContinueAction.State, str]] = ...) -> None: ...

class ContinueHint(_message.Message):
    __slots__ = ("message",)
    MESSAGE_FIELD_NUMBER: _ClassVar[int]
    message: str
    def __init__(self, message: _Optional[str] = ...) -> None: ...

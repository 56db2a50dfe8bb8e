from ssl_protocol.state import ssl_gc_common_pb2 as _ssl_gc_common_pb2
from ssl_protocol.rcon import ssl_gc_rcon_pb2 as _ssl_gc_rcon_pb2
from google.protobuf.internal import containers as _containers
from google.protobuf.internal import enum_type_wrapper as _enum_type_wrapper
from google.protobuf import descriptor as _descriptor
from google.protobuf import message as _message
from collections.abc import Iterable as _Iterable, Mapping as _Mapping
from typing import ClassVar as _ClassVar, Optional as _Optional, Union as _Union

DESCRIPTOR: _descriptor.FileDescriptor

class RemoteControlRequestType(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    UNKNOWN_REQUEST_TYPE: _ClassVar[RemoteControlRequestType]
    EMERGENCY_STOP: _ClassVar[RemoteControlRequestType]
    ROBOT_SUBSTITUTION: _ClassVar[RemoteControlRequestType]
    TIMEOUT: _ClassVar[RemoteControlRequestType]
    CHALLENGE_FLAG: _ClassVar[RemoteControlRequestType]
    CHANGE_KEEPER_ID: _ClassVar[RemoteControlRequestType]
    STOP_TIMEOUT: _ClassVar[RemoteControlRequestType]
    FAIL_BALLPLACEMENT: _ClassVar[RemoteControlRequestType]
UNKNOWN_REQUEST_TYPE: RemoteControlRequestType
EMERGENCY_STOP: RemoteControlRequestType
ROBOT_SUBSTITUTION: RemoteControlRequestType
TIMEOUT: RemoteControlRequestType
CHALLENGE_FLAG: RemoteControlRequestType
CHANGE_KEEPER_ID: RemoteControlRequestType
STOP_TIMEOUT: RemoteControlRequestType
FAIL_BALLPLACEMENT: RemoteControlRequestType

class RemoteControlRegistration(_message.Message):
    __slots__ = ("team", "signature")
    TEAM_FIELD_NUMBER: _ClassVar[int]
    SIGNATURE_FIELD_NUMBER: _ClassVar[int]
    team: _ssl_gc_common_pb2.Team
    signature: _ssl_gc_rcon_pb2.Signature
    def __init__(self, team: _Optional[_Union[_ssl_gc_common_pb2.Team, str]] = ..., signature: _Optional[_Union[_ssl_gc_rcon_pb2.Signature, _Mapping]] = ...) -> None: ...

class RemoteControlToController(_message.Message):
    __slots__ = ("signature", "request", "desired_keeper", "request_robot_substitution", "request_timeout", "request_emergency_stop")
    class Request(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
        __slots__ = ()
        UNKNOWN: _ClassVar[RemoteControlToController.Request]
        PING: _ClassVar[RemoteControlToController.Request]
        CHALLENGE_FLAG: _ClassVar[RemoteControlToController.Request]
        STOP_TIMEOUT: _ClassVar[RemoteControlToController.Request]
        FAIL_BALLPLACEMENT: _ClassVar[RemoteControlToController.Request]
    UNKNOWN: RemoteControlToController.Request
    PING: RemoteControlToController.Request
    CHALLENGE_FLAG: RemoteControlToController.Request
    STOP_TIMEOUT: RemoteControlToController.Request
    FAIL_BALLPLACEMENT: RemoteControlToController.Request
    SIGNATURE_FIELD_NUMBER: _ClassVar[int]
    REQUEST_FIELD_NUMBER: _ClassVar[int]
    DESIRED_KEEPER_FIELD_NUMBER: _ClassVar[int]
    REQUEST_ROBOT_SUBSTITUTION_FIELD_NUMBER: _ClassVar[int]
    REQUEST_TIMEOUT_FIELD_NUMBER: _ClassVar[int]
    REQUEST_EMERGENCY_STOP_FIELD_NUMBER: _ClassVar[int]
    signature: _ssl_gc_rcon_pb2.Signature
    request: RemoteControlToController.Request
    desired_keeper: int
    request_robot_substitution: bool
    request_timeout: bool
    request_emergency_stop: bool
    def __init__(self, signature: _Optional[_Union[_ssl_gc_rcon_pb2.Signature, _Mapping]] = ..., request: _Optional[_Union[RemoteControlToController.Request, str]] = ..., desired_keeper: _Optional[int] = ..., request_robot_substitution: _Optional[bool] = ..., request_timeout: _Optional[bool] = ..., request_emergency_stop: _Optional[bool] = ...) -> None: ...

class ControllerToRemoteControl(_message.Message):
    __slots__ = ("controller_reply", "state")
    CONTROLLER_REPLY_FIELD_NUMBER: _ClassVar[int]
    STATE_FIELD_NUMBER: _ClassVar[int]
    controller_reply: _ssl_gc_rcon_pb2.ControllerReply
    state: RemoteControlTeamState
    def __init__(self, controller_reply: _Optional[_Union[_ssl_gc_rcon_pb2.ControllerReply, _Mapping]] = ..., state: _Optional[_Union[RemoteControlTeamState, _Mapping]] = ...) -> None: ...

class RemoteControlTeamState(_message.Message):
    __slots__ = ("team", "available_requests", "active_requests", "keeper_id", "emergency_stop_in", "timeouts_left", "timeout_time_left", "challenge_flags_left", "max_robots", "robots_on_field", "yellow_cards_due", "can_substitute_robot", "bot_substitutions_left", "bot_substitution_time_left")
    TEAM_FIELD_NUMBER: _ClassVar[int]
    AVAILABLE_REQUESTS_FIELD_NUMBER: _ClassVar[int]
    ACTIVE_REQUESTS_FIELD_NUMBER: _ClassVar[int]
    KEEPER_ID_FIELD_NUMBER: _ClassVar[int]
    EMERGENCY_STOP_IN_FIELD_NUMBER: _ClassVar[int]
    TIMEOUTS_LEFT_FIELD_NUMBER: _ClassVar[int]
    TIMEOUT_TIME_LEFT_FIELD_NUMBER: _ClassVar[int]
    CHALLENGE_FLAGS_LEFT_FIELD_NUMBER: _ClassVar[int]
    MAX_ROBOTS_FIELD_NUMBER: _ClassVar[int]
    ROBOTS_ON_FIELD_FIELD_NUMBER: _ClassVar[int]
    YELLOW_CARDS_DUE_FIELD_NUMBER: _ClassVar[int]
    CAN_SUBSTITUTE_ROBOT_FIELD_NUMBER: _ClassVar[int]
    BOT_SUBSTITUTIONS_LEFT_FIELD_NUMBER: _ClassVar[int]
    BOT_SUBSTITUTION_TIME_LEFT_FIELD_NUMBER: _ClassVar[int]
    team: _ssl_gc_common_pb2.Team
    available_requests: _containers.RepeatedScalarFieldContainer[RemoteControlRequestType]
    active_requests: _containers.RepeatedScalarFieldContainer[RemoteControlRequestType]
    keeper_id: int
    emergency_stop_in: float
    timeouts_left: int
    timeout_time_left: float
    challenge_flags_left: int
    max_robots: int
    robots_on_field: int
    yellow_cards_due: _containers.RepeatedScalarFieldContainer[float]
    can_substitute_robot: bool
    bot_substitutions_left: int
    bot_substitution_time_left: float
    def __init__(self, team: _Optional[_Union[_ssl_gc_common_pb2.Team, str]] = ..., available_requests: _Optional[_Iterable[_Union[RemoteControlRequestType, str]]] = ..., active_requests: _Optional[_Iterable[_Union[RemoteControlRequestType, str]]] = ..., keeper_id: _Optional[int] = ..., emergency_stop_in: _Optional[float] = ..., timeouts_left: _Optional[int] = ..., timeout_time_left: _Optional[float] = ..., challenge_flags_left: _Optional[int] = ..., max_robots: _Optional[int] = ..., robots_on_field: _Optional[int] = ..., yellow_cards_due: _Optional[_Iterable[float]] = ..., can_substitute_robot: _Optional[bool] = ..., bot_substitutions_left: _Optional[int] = ..., bot_substitution_time_left: _Optional[float] = ...) -> None: ...

from google.protobuf.internal import enum_type_wrapper as _enum_type_wrapper
from google.protobuf import descriptor as _descriptor
from google.protobuf import message as _message
from typing import ClassVar as _ClassVar, Optional as _Optional, Union as _Union

DESCRIPTOR: _descriptor.FileDescriptor

class ControllerReply(_message.Message):
    __slots__ = ("status_code", "reason", "next_token", "verification")
    class StatusCode(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
        __slots__ = ()
        UNKNOWN_STATUS_CODE: _ClassVar[ControllerReply.StatusCode]
        OK: _ClassVar[ControllerReply.StatusCode]
        REJECTED: _ClassVar[ControllerReply.StatusCode]
    UNKNOWN_STATUS_CODE: ControllerReply.StatusCode
    OK: ControllerReply.StatusCode
    REJECTED: ControllerReply.StatusCode
    class Verification(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
        __slots__ = ()
        UNKNOWN_VERIFICATION: _ClassVar[ControllerReply.Verification]
        VERIFIED: _ClassVar[ControllerReply.Verification]
        UNVERIFIED: _ClassVar[ControllerReply.Verification]
    UNKNOWN_VERIFICATION: ControllerReply.Verification
    VERIFIED: ControllerReply.Verification
    UNVERIFIED: ControllerReply.Verification
    STATUS_CODE_FIELD_NUMBER: _ClassVar[int]
    REASON_FIELD_NUMBER: _ClassVar[int]
    NEXT_TOKEN_FIELD_NUMBER: _ClassVar[int]
    VERIFICATION_FIELD_NUMBER: _ClassVar[int]
    status_code: ControllerReply.StatusCode
    reason: str
    next_token: str
    verification: ControllerReply.Verification
    def __init__(self, status_code: _Optional[_Union[ControllerReply.StatusCode, str]] = ..., reason: _Optional[str] = ..., next_token: _Optional[str] = ..., verification: _Optional[_Union[ControllerReply.Verification, str]] = ...) -> None: ...

class Signature(_message.Message):
    __slots__ = ("token", "pkcs1v15")
    TOKEN_FIELD_NUMBER: _ClassVar[int]
    PKCS1V15_FIELD_NUMBER: _ClassVar[int]
    token: str
    pkcs1v15: bytes
    def __init__(self, token: _Optional[str] = ..., pkcs1v15: _Optional[bytes] = ...) -> None: ...

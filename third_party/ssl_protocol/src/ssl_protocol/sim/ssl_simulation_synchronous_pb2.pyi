from ssl_protocol.vision import ssl_vision_detection_pb2 as _ssl_vision_detection_pb2
from ssl_protocol.sim import ssl_simulation_robot_feedback_pb2 as _ssl_simulation_robot_feedback_pb2
from ssl_protocol.sim import ssl_simulation_robot_control_pb2 as _ssl_simulation_robot_control_pb2
from ssl_protocol.sim import ssl_simulation_control_pb2 as _ssl_simulation_control_pb2
from google.protobuf.internal import containers as _containers
from google.protobuf import descriptor as _descriptor
from google.protobuf import message as _message
from collections.abc import Iterable as _Iterable, Mapping as _Mapping
from typing import ClassVar as _ClassVar, Optional as _Optional, Union as _Union

DESCRIPTOR: _descriptor.FileDescriptor

class SimulationSyncRequest(_message.Message):
    __slots__ = ("sim_step", "simulator_command", "robot_control")
    SIM_STEP_FIELD_NUMBER: _ClassVar[int]
    SIMULATOR_COMMAND_FIELD_NUMBER: _ClassVar[int]
    ROBOT_CONTROL_FIELD_NUMBER: _ClassVar[int]
    sim_step: float
    simulator_command: _ssl_simulation_control_pb2.SimulatorCommand
    robot_control: _ssl_simulation_robot_control_pb2.RobotControl
    def __init__(self, sim_step: _Optional[float] = ..., simulator_command: _Optional[_Union[_ssl_simulation_control_pb2.SimulatorCommand, _Mapping]] = ..., robot_control: _Optional[_Union[_ssl_simulation_robot_control_pb2.RobotControl, _Mapping]] = ...) -> None: ...

class SimulationSyncResponse(_message.Message):
    __slots__ = ("detection", "robot_control_response")
    DETECTION_FIELD_NUMBER: _ClassVar[int]
    ROBOT_CONTROL_RESPONSE_FIELD_NUMBER: _ClassVar[int]
    detection: _containers.RepeatedCompositeFieldContainer[_ssl_vision_detection_pb2.SSL_DetectionFrame]
    robot_control_response: _ssl_simulation_robot_feedback_pb2.RobotControlResponse
    def __init__(self, detection: _Optional[_Iterable[_Union[_ssl_vision_detection_pb2.SSL_DetectionFrame, _Mapping]]] = ..., robot_control_response: _Optional[_Union[_ssl_simulation_robot_feedback_pb2.RobotControlResponse, _Mapping]] = ...) -> None: ...

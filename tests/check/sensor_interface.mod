MODULE sensor_interface
  ! ReadVar and ReadBlock belong to the Sensor Interface option, not to base RobotWare:
  ! `rapidvc check` names the option (tests/cli/check_sensor_interface.toml).

  PROC main()
    VAR num value;
    value := ReadVar(1, 2);
    ReadBlock 1, 2, "HOME:/block.txt";
  ENDPROC
ENDMODULE

MODULE cfg_data
  ! ReadCfgData and WriteCfgData against the CFG files next to this module (EIO.cfg,
  ! MOC.cfg, SYS.cfg). SaveCfgData writes files: tests/system.rs runs it with --save-cfg in
  ! a temporary directory. The examples of ABB's "RAPID Instructions, Functions and Data
  ! types" are named where a test follows one.

  ! ReadCfgData example 1: the calibration offset of axis 1 into a num.
  PROC test_read_num()
    VAR num offset1;
    ReadCfgData "/MOC/MOTOR_CALIB/rob1_1", "cal_offset", offset1;
    Assert offset1 = 1.2345;
    ReadCfgData "/MOC/MOTOR_CALIB/rob1_2", "cal_offset", offset1;
    Assert offset1 = -0.5;
  ENDPROC

  ! ReadCfgData example 2: the I/O device of the signal process_error into a string.
  PROC test_read_string()
    VAR string io_device;
    ReadCfgData "/EIO/EIO_SIGNAL/process_error", "Device", io_device;
    Assert io_device = "d652";
    ReadCfgData "/eio/eio_signal/DOGRIPPER", "signaltype", io_device;
    Assert io_device = "DO" \Msg:="names compare case-insensitively";
  ENDPROC

  PROC test_read_bool_and_dnum()
    VAR bool flag;
    VAR dnum big;
    ReadCfgData "/EIO/EIO_SIGNAL/diPartPresent", "Invert", flag;
    Assert flag;
    ReadCfgData "/EIO/EIO_SIGNAL/doGripper", "Invert", flag;
    Assert NOT flag \Msg:="a flag the file leaves out is FALSE";
    ReadCfgData "/SYS/CAB_TASKS/T_ROB1", "MotionTask", flag;
    Assert flag;
    ReadCfgData "/EIO/EIO_SIGNAL/aoSpeed", "MaxLog", big;
    Assert big = 2000;
  ENDPROC

  ! ReadCfgData example 3: every signal of the device USERIO with \ListNo.
  PROC test_read_list()
    VAR num list_index := 0;
    VAR string read_str;
    VAR string names := "";
    WHILE list_index <> END_OF_LIST DO
      ReadCfgData "/EIO/EIO_SIGNAL/Device/USERIO", "Name", read_str \ListNo:=list_index;
      names := names + read_str + ";";
    ENDWHILE
    Assert names = "doGripper;doVacuum;diPartPresent;";
    ReadCfgData "/EIO/EIO_SIGNAL/SignalType/AO", "Name", read_str;
    Assert read_str = "aoSpeed";
  ENDPROC

  PROC test_not_found()
    VAR num errs := 0;
    VAR string s;
    ReadCfgData "/EIO/EIO_SIGNAL/no_signal", "Device", s;
    ReadCfgData "/EIO/EIO_SIGNAL/doGripper", "NoAttribute", s;
    ReadCfgData "/PROC/ANY_TYPE/x", "Name", s;
    ReadCfgData "EIO/EIO_SIGNAL/doGripper", "Device", s;
    Assert errs = 4;
  ERROR
    Assert ERRNO = ERR_CFG_NOTFND;
    errs := errs + 1;
    TRYNEXT;
  ENDPROC

  PROC test_wrong_type()
    VAR num n;
    ReadCfgData "/EIO/EIO_SIGNAL/doGripper", "Device", n;
    Assert FALSE \Msg:="not reached";
  ERROR
    Assert ERRNO = ERR_CFG_ILLTYPE;
  ENDPROC

  PROC test_list_out_of_bounds()
    VAR num list_index := 3;
    VAR string s;
    ReadCfgData "/EIO/EIO_SIGNAL/Device/USERIO", "Name", s \ListNo:=list_index;
    Assert FALSE \Msg:="not reached";
  ERROR
    Assert ERRNO = ERR_CFG_OUTOFBOUNDS;
  ENDPROC

  ! WriteCfgData examples: a num and a string parameter; reads see the new values.
  PROC test_write_and_read_back()
    VAR num offset1;
    VAR string dev;
    VAR bool flag;
    WriteCfgData "/MOC/MOTOR_CALIB/rob1_1", "cal_offset", 1.5;
    ReadCfgData "/MOC/MOTOR_CALIB/rob1_1", "cal_offset", offset1;
    Assert offset1 = 1.5;
    WriteCfgData "/EIO/EIO_SIGNAL/process_error", "Device", "d651";
    ReadCfgData "/EIO/EIO_SIGNAL/process_error", "Device", dev;
    Assert dev = "d651";
    WriteCfgData "/EIO/EIO_SIGNAL/doGripper", "Invert", TRUE;
    ReadCfgData "/EIO/EIO_SIGNAL/doGripper", "Invert", flag;
    Assert flag;
    WriteCfgData "/EIO/EIO_SIGNAL/diPartPresent", "Invert", FALSE;
    ReadCfgData "/EIO/EIO_SIGNAL/diPartPresent", "Invert", flag;
    Assert NOT flag;
  ENDPROC

  ! Every signal of USERIO moves to USERIO2: a written instance no longer matches, so the
  ! first match is written each time until \ListNo comes back as END_OF_LIST.
  PROC test_write_list()
    VAR num list_index := 0;
    VAR num writes := 0;
    VAR string dev;
    WHILE list_index <> END_OF_LIST DO
      list_index := 0;
      WriteCfgData "/EIO/EIO_SIGNAL/Device/USERIO", "Device", "USERIO2" \ListNo:=list_index;
      writes := writes + 1;
    ENDWHILE
    Assert writes = 3;
    ReadCfgData "/EIO/EIO_SIGNAL/diPartPresent", "Device", dev;
    Assert dev = "USERIO2";
    ReadCfgData "/EIO/EIO_SIGNAL/Device/USERIO", "Name", dev;
    Assert FALSE \Msg:="not reached";
  ERROR
    Assert ERRNO = ERR_CFG_NOTFND \Msg:="nothing is left on USERIO";
  ENDPROC

  PROC test_write_limit()
    WriteCfgData "/EIO/EIO_SIGNAL/doVacuum", "Name", "doGripper";
    Assert FALSE \Msg:="not reached";
  ERROR
    Assert ERRNO = ERR_CFG_LIMIT \Msg:="two signals cannot have one name";
  ENDPROC

  PROC test_write_wrong_type()
    WriteCfgData "/EIO/EIO_SIGNAL/aoSpeed", "MaxLog", "fast";
    Assert FALSE \Msg:="not reached";
  ERROR
    Assert ERRNO = ERR_CFG_ILLTYPE;
  ENDPROC
ENDMODULE

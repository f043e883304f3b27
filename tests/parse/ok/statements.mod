MODULE Statements
  PROC all()
    ! Assignments to a name, an element, a component chain and a mix
    total := 0;
    grid{2, 3} := 5;
    spot.trans.x := spot.trans.x + 10;
    shelves{idx}.corner.z := -1;

    ! Procedure calls: required, optional (with and without a comma), switches,
    ! named and conditional arguments
    Stop;
    MoveL spot, v100, z10, gripTool;
    MoveL spot, v100, z10, gripTool \WObj:=table;
    MoveL spot, v100, z10, gripTool, \WObj:=table;
    MoveJ \Conc, spot, v500, fine, gripTool;
    TPWrite "Count: " \Num:=total;
    SearchL \Stop, sensorIn, found, spot, v100, gripTool;
    Report code:=3, text:="ok";
    Forward level \Fast?Fast \Level ?level;
    WaitTime (0.5);
    MoveL Offs(spot, 0, 0, 10),   ! comments between the lines of an argument list
      v100,
      ! a whole comment line
      z10, gripTool
      \WObj:=table;
    WaitTime (0.5) + 1;

    ! Late binding
    %"step" + NumToStr(idx, 0)%;
    %procName% 1, \Fast;

    ! IF forms
    IF total > 3 THEN
      total := 0;
    ELSEIF total = -1 THEN
      total := 1;
    ELSEIF total < 0 THEN
      total := 2;
    ELSE
      total := 3;
    ENDIF
    IF ready THEN
    ENDIF
    IF total > 3 total := 0;
    IF NOT ready GOTO finish;
    IF total = 0 RETURN;

    ! Loops
    WHILE total < 10 DO
      total := total + 1;
    ENDWHILE
    FOR i FROM 1 TO 10 DO
      grid{1, i} := i;
    ENDFOR
    FOR j FROM 10 TO 1 STEP -2 DO
      Incr total;
    ENDFOR

    ! TEST
    TEST total
    CASE 1, 2, 3:
      total := 0;
    CASE 4:
    DEFAULT:
      total := -1;
    ENDTEST
    TEST mode
    CASE 1:
      Stop;
    ENDTEST

    ! Labels, GOTO, RETURN, RAISE, EXIT, CONNECT
    again:
    GOTO again;
    finish:
    CONNECT sensorInt WITH onSignal;
    CONNECT events{2} WITH onSignal;
    RAISE ERR_MINE;
    EXIT;
    RETURN;
  ERROR
    RAISE;
    RETRY;
    TRYNEXT;
    RETURN;
  ENDPROC
ENDMODULE

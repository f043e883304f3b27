MODULE Decls
  ! Type definitions
  RECORD shelf
    num slots;      ! a comment after a component
    ! a comment line inside the record
    pos corner;
    string label{3};
  ENDRECORD
  LOCAL RECORD tiny
    bool flag;
  ENDRECORD
  ALIAS num weight;
  LOCAL ALIAS shelf rack;

  ! Data
  VAR num plain;
  VAR num withInit := 42;
  LOCAL VAR bool ready := TRUE;
  PERS string title := "Main ""hall""";
  PERS num shared;
  TASK PERS tooldata gripTool := [TRUE, [[0, 0, 150], [1, 0, 0, 0]],
    [2.5, [0, 0, 60], [1, 0, 0, 0], 0, 0, 0]];
  LOCAL TASK PERS num perTask := 1;
  ! As controller backups write them: the same as plain VAR and CONST.
  TASK VAR num taskVar := 2;
  TASK CONST num taskConst := 3;
  CONST num row{3} := [1, 2, 3];
  CONST num grid{2, 3} := [[1, 2, 3],
                           ! a comment inside a multi-line aggregate
                           [4, 5, 6]];
  VAR num cube{2, 2, 2};
  CONST robtarget home := [[600, -0.5, 800.25], [0.707107, 0, 0.707107, 0], [0, 0, -1, 0],
    [9E+09, 9E+09, 9E+09, 9E+09, 9E+09, 9E+09]];
  VAR shelf lower := [4, [0, 0, 0], ["a", "b", "c"]];
  CONST num size := 2 * row{2} + 1;
ENDMODULE

MODULE data_by_name
  ! Data reached by name (GetDataVal, SetDataVal) and data asked about itself (ArgName,
  ! IsPers, IsVar, Type). Examples of ABB's "RAPID Instructions, Functions and Data types"
  ! are named where a test follows one.

  VAR num reg1 := 11;
  VAR num reg2 := 22;
  PERS num counter := 0;
  CONST num limit := 100;
  VAR string label := "start";
  VAR num table{3} := [1, 2, 3];
  VAR pos where := [1, 2, 3];
  LOCAL VAR num hidden := 7;
  VAR num caught := 0;

  ! GetDataVal example 1: GetDataVal "reg"+ValToStr(ReadNum(mycom)), value (the register
  ! number is read at run time).
  PROC test_getdataval_by_computed_name()
    VAR num value;
    VAR num n := 2;
    GetDataVal "reg" + ValToStr(n), value;
    Assert value = 22;
    GetDataVal "REG1", value;
    Assert value = 11 \Msg:="names are case-insensitive";
    GetDataVal "limit", value;
    Assert value = 100 \Msg:="constants can be read";
    GetDataVal "hidden", value;
    Assert value = 7 \Msg:="LOCAL data of the calling module";
  ENDPROC

  ! GetDataVal example 3: an array copied whole by its name.
  PROC test_getdataval_array_and_record()
    VAR num copy{3};
    VAR pos p;
    VAR string s;
    GetDataVal "table", copy;
    Assert copy{3} = 3;
    GetDataVal "where", p;
    Assert p.z = 3;
    GetDataVal "label", s;
    Assert s = "start";
  ENDPROC

  PROC test_getdataval_routine_data()
    VAR num mine := 42;
    VAR num v;
    GetDataVal "mine", v;
    Assert v = 42;
  ENDPROC

  ! A signal of the I/O configuration (tests/rapid/EIO.cfg) reached by name: GetDataVal
  ! connects a signal variable to it, as AliasIO does (a communication module picks its
  ! signals by name this way). A signal of another kind, or no such signal, is an error.
  VAR signaldo out_by_name;
  VAR signalao analog_by_name;
  VAR signaldi in_by_name;

  PROC test_getdataval_signal()
    GetDataVal "do" + ValToStr(2), out_by_name;
    SetDO out_by_name, 1;
    Assert DOutput(do2) = 1;
    SetDO do2, 0;
    GetDataVal "AO1", analog_by_name;
    SetAO analog_by_name, 12.5;
    Assert AOutput(ao1) = 12.5;
    SetAO ao1, 0;
    caught := 0;
    GetDataVal "do1", in_by_name;
    Assert caught = ERR_SYMBOL_TYPE;
    caught := 0;
    GetDataVal "no_such_signal", out_by_name;
    Assert caught = ERR_SYM_ACCESS;
  ERROR
    caught := ERRNO;
    TRYNEXT;
  ENDPROC

  ! SetDataVal example 1: SetDataVal "reg"+ValToStr(ReadNum(mycom)), value.
  PROC test_setdataval()
    VAR num n := 1;
    VAR num other{3} := [7, 8, 9];
    SetDataVal "reg" + ValToStr(n), 99;
    Assert reg1 = 99;
    SetDataVal "counter", counter + 5;
    Assert counter = 5 \Msg:="persistents can be set";
    SetDataVal "table", other;
    Assert table{2} = 8;
    SetDataVal "label", "changed";
    Assert label = "changed";
    reg1 := 11;
    counter := 0;
    table := [1, 2, 3];
    label := "start";
  ENDPROC

  ! The errors ABB names: no such data or a constant (ERR_SYM_ACCESS), another type
  ! (ERR_SYMBOL_TYPE), other dimensions (ERR_INVDIM).
  PROC test_by_name_errors()
    VAR num v;
    VAR string s;
    VAR num two{2};
    caught := 0;
    GetDataVal "nosuchdata", v;
    Assert caught = ERR_SYM_ACCESS;
    caught := 0;
    GetDataVal "reg1", s;
    Assert caught = ERR_SYMBOL_TYPE;
    caught := 0;
    GetDataVal "table", v;
    Assert caught = ERR_INVDIM;
    caught := 0;
    GetDataVal "table", two;
    Assert caught = ERR_INVDIM;
    caught := 0;
    SetDataVal "limit", 5;
    Assert caught = ERR_SYM_ACCESS;
    Assert limit = 100;
    caught := 0;
    SetDataVal "reg1", "text";
    Assert caught = ERR_SYMBOL_TYPE;
    Assert reg1 = 11;
  ERROR
    caught := ERRNO;
    TRYNEXT;
  ENDPROC

  ! ArgName example 1: the name of the data object passed (here through an INOUT
  ! parameter: rapidvc follows reference parameters to the caller's data).
  PROC test_argname()
    VAR num mine := 5;
    Assert ArgName(reg1) = "reg1";
    Assert ArgName(counter) = "counter";
    Assert ArgName(mine) = "mine";
    Assert name_of(reg2) = "reg2";
    Assert name_of(mine) = "mine";
  ENDPROC

  FUNC string name_of(INOUT num par1)
    RETURN ArgName(par1);
  ENDFUNC

  ! ArgName of an expression: ERR_ARGNAME, or \ErrorNumber set and an empty name.
  PROC test_argname_errors()
    VAR errnum err := -1;
    Assert ArgName(reg1 + 1 \ErrorNumber:=err) = "";
    Assert err = ERR_ARGNAME;
    Assert ArgName(reg1 \ErrorNumber:=err) = "reg1";
    Assert err = 0;
    caught := 0;
    label := ArgName(where.x);
    Assert caught = ERR_ARGNAME;
    label := "start";
  ERROR
    caught := ERRNO;
    TRYNEXT;
  ENDPROC

  ! IsPers and IsVar examples: a routine that asks what its INOUT parameter was given.
  PROC test_ispers_isvar()
    VAR num mine := 0;
    Assert kind_of(counter) = "PERS";
    Assert kind_of(reg1) = "VAR";
    Assert kind_of(mine) = "VAR";
    Assert IsPers(counter) AND (NOT IsVar(counter));
    Assert IsVar(reg1) AND (NOT IsPers(reg1));
  ENDPROC

  FUNC string kind_of(INOUT num x)
    IF IsPers(x) THEN
      RETURN "PERS";
    ELSEIF IsVar(x) THEN
      RETURN "VAR";
    ENDIF
    RETURN "?";
  ENDFUNC

  ! Type example: Type(refname) is "num" for a num.
  PROC test_type()
    VAR num mine := 0;
    Assert Type(reg1) = "num";
    Assert Type(mine) = "num";
    Assert Type(label) = "string";
    Assert Type(where) = "pos";
    Assert Type(where.x) = "num";
    Assert Type(table) = "num" \Msg:="an array answers with its element type";
    Assert Type(tool0) = "tooldata";
    Assert Type(counter \BaseName) = "num";
  ENDPROC
ENDMODULE

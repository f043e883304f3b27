MODULE data_search
  ! SetDataSearch, GetNextSym, GetDataVal/SetDataVal \Block and SetAllDataVal on this
  ! module's data. Where a test follows an example of the RAPID reference manual, the
  ! comment names it.
  VAR bool mybool1 := FALSE;
  VAR bool mybool2 := FALSE;
  LOCAL VAR bool mylocal := FALSE;
  PERS bool mypers := FALSE;
  CONST bool myconst := FALSE;
  VAR num mynum := 0;
  VAR num othernum := 5;

  ! SetDataSearch's example: "SetDataSearch "bool" \Object:="my.*" \InMod:="mymod"
  ! \LocalSym; WHILE GetNextSym(name,block) DO SetDataVal name\Block:=block,truevar;".
  PROC test_set_data_search_local_sym()
    VAR datapos block;
    VAR string name;
    VAR bool truevar := TRUE;
    VAR bool got;
    mylocal := FALSE;
    SetDataSearch "bool" \Object:="my.*" \InMod:="data_search" \LocalSym;
    WHILE GetNextSym(name, block) DO
      SetDataVal name \Block:=block, truevar;
    ENDWHILE
    Assert mylocal;
    Assert NOT mybool1;
    GetDataVal "mylocal" \Block:=block, got;
    Assert got;
  ENDPROC

  ! Storage classes and the regular expression: variables matching ^mybool[0-9]$.
  PROC test_search_storage_and_pattern()
    VAR datapos block;
    VAR string name;
    VAR string names := "";
    SetDataSearch "bool" \Object:="^mybool[0-9]$" \VarSym;
    WHILE GetNextSym(name, block) DO
      names := names + name + ",";
    ENDWHILE
    Assert names = "mybool1,mybool2,";
    names := "";
    SetDataSearch "bool" \PersSym \ConstSym \InTask;
    WHILE GetNextSym(name, block) DO
      names := names + name + ",";
    ENDWHILE
    Assert names = "mypers,myconst,";
    names := "";
    SetDataSearch "num" \GlobalSym;
    WHILE GetNextSym(name, block) DO
      names := names + name + ",";
    ENDWHILE
    ! The controller's USER module (reg1 … reg5) is searched too, as any module of the task.
    Assert names = "reg1,reg2,reg3,reg4,reg5,mynum,othernum,";
  ENDPROC

  ! An unknown type is ERR_SYMBOL_TYPE; a bad regular expression ERR_ARGVALERR.
  PROC test_search_errors()
    VAR errnum err := 0;
    SetDataSearch "no_such_type";
    Assert err = ERR_SYMBOL_TYPE;
    err := 0;
    SetDataSearch "num" \Object:="(";
    Assert err = ERR_ARGVALERR;
  ERROR
    err := ERRNO;
    TRYNEXT;
  ENDPROC

  ! SetAllDataVal's example: "SetAllDataVal "num"\Object:="my.*", 0;" — every num whose
  ! name matches; constants are left alone; a value of another type is ERR_SYMBOL_TYPE.
  PROC test_set_all_data_val()
    VAR errnum err := 0;
    mynum := 3;
    othernum := 5;
    SetAllDataVal "num" \Object:="^my", 42;
    Assert mynum = 42;
    Assert othernum = 5;
    SetAllDataVal "bool" \Object:="^my", TRUE;
    Assert mybool1 AND mybool2 AND mypers AND mylocal;
    Assert NOT myconst;
    SetAllDataVal "num", "text";
    Assert err = ERR_SYMBOL_TYPE;
  ERROR
    err := ERRNO;
    TRYNEXT;
  ENDPROC
ENDMODULE

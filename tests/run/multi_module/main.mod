MODULE mainmod
  ! Several modules form one program: global routines and data are shared, LOCAL ones are
  ! private to their module and hide global ones of the same name, PERS data declared in
  ! two modules is one object.
  PERS num shared := 1;
  LOCAL VAR string who := "main";

  LOCAL PROC hello()
    TPWrite "hello from the main module (" + who + ")";
  ENDPROC

  PROC main()
    hello;
    helper_hello;
    shared := shared + 1;
    TPWrite "shared after main: " \Num:=shared;
    bump_shared;
    TPWrite "shared after helper: " \Num:=shared;
    TPWrite "twice(21) = " \Num:=twice(21);
  ENDPROC
ENDMODULE

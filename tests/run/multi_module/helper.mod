MODULE helpermod
  PERS num shared := 1;
  LOCAL VAR string who := "helper";

  LOCAL PROC hello()
    TPWrite "hello from the helper module (" + who + ")";
  ENDPROC

  PROC helper_hello()
    hello;
  ENDPROC

  PROC bump_shared()
    shared := shared * 10;
  ENDPROC

  FUNC num twice(num x)
    RETURN 2 * x;
  ENDFUNC
ENDMODULE

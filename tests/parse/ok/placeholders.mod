MODULE Draft
  <DDN>
  <RDN>
  PROC work(num a, <PAR>)
    <SMT>
    x := <EXP>;
    <VAR> := 1;
    Tool <ARG>, 3;
    IF a > 0 <SMT>
    IF a < 0 <SMT>;
    IF a > 0 THEN
      <SMT>;
    <EIT>
    ENDIF
    TEST a
    <CSE>
    CASE 1:
      Stop;
    ENDTEST
  ENDPROC
ENDMODULE

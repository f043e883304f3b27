MODULE argname_in
  ! ArgName follows INOUT parameters to the caller's data, but an IN parameter holds a copy
  ! whose origin rapidvc does not keep: the run stops with an error that says so, at the
  ! call (docs/rapid.md, "Data by name").
  VAR num chales := 5;

  PROC main()
    TPWrite "through INOUT: " + by_ref(chales);
    proc1 chales;
    TPWrite "not reached";
  ENDPROC

  FUNC string by_ref(INOUT num par)
    RETURN ArgName(par);
  ENDFUNC

  ! ArgName example 1 of ABB's "RAPID Instructions, Functions and Data types" passes an IN
  ! parameter.
  PROC proc1(num par1)
    TPWrite "Argument name " + ArgName(par1) + " with value " \Num:=par1;
  ENDPROC
ENDMODULE

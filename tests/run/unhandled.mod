MODULE unhandled
  ! An error nobody handles stops the program: ERR name and number, the line, the call stack.
  FUNC num ratio(num a, num b)
    RETURN a / b;
  ENDFUNC

  PROC compute(num n)
    TPWrite "ratio: " \Num:=ratio(10, n);
  ENDPROC

  PROC main()
    compute 4;
    compute 0;
    TPWrite "never printed";
  ENDPROC
ENDMODULE

MODULE Encoding
  ! Latin-1 byte in a comment: café, and in a string below
  CONST string place := "garçon";
  PROC p()
    x := 0;
  ENDPROC
ENDMODULE

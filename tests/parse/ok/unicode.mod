MODULE Unicode
  ! UTF-8 in a comment: Größe, 日本
  CONST string greet := "Grüße";
　
  PROC p()
		x := 1;　! ideographic space before this comment
  ENDPROC
ENDMODULE

%%%
  VERSION:1
  LANGUAGE:ENGLISH
%%%
! A comment before the first module (CRLF line ends in this file)

MODULE FirstPart(SYSMODULE, NOSTEPIN, READONLY)
  VAR num counter := 0;
ENDMODULE
! Between modules
module SecondPart (viewonly, NoView)
  proc run()
    counter := counter + 1;  ! trailing comment
  endproc
EndModule

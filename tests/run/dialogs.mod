! args: --answers dialogs.answers
MODULE dialogs
  ! The operator dialogs answered from tests/run/dialogs.answers; values and dialogs from
  ! the examples of the RAPID reference (named at each one).
  CONST listitem list{3} := [["", "Item 1"], ["", "Item 2"], ["", "Item 3"]];
  CONST string my_message{2} := ["The application is still running.", "Skip the step?"];
  CONST string my_buttons{2} := ["OK", "Skip"];
  VAR num reg1;
  VAR errnum errvar;

  PROC main()
    VAR btnres answer;
    VAR num n;
    VAR dnum d;
    VAR string s;
    VAR num list_item;
    VAR btnres button_answer;
    ! UIClientExist example: answers can come (from the answers file).
    IF UIClientExist() THEN
      TPWrite "an operator can answer";
    ENDIF
    ! TPReadFK example 1: keys 4 and 5 are Yes and No; the file answers "Yes" -> 4.
    TPReadFK reg1, "More?", stEmpty, stEmpty, stEmpty, "Yes", "No";
    TPWrite "reg1 = " \Num:=reg1;
    ! By number: F5.
    TPReadFK reg1, "More?", stEmpty, stEmpty, stEmpty, "Yes", "No";
    TPWrite "reg1 = " \Num:=reg1;
    ! TPReadFK example 2: nobody answers (!noanswer) within \MaxTime 600 s.
    TPReadFK reg1, "Go to service position?", stEmpty, stEmpty, stEmpty, "Yes", "No"
      \MaxTime:=600 \DIBreak:=di1 \BreakFlag:=errvar;
    IF errvar = ERR_TP_MAXTIME TPWrite "timed out, as in the example";
    ! \DOBreak: do1 is set after 2 s while the dialog waits.
    SetDO \SDelay:=2, do1, 1;
    TPReadFK reg1, "Wait for do1", "A", stEmpty, stEmpty, stEmpty, stEmpty
      \MaxTime:=600 \DOBreak:=do1 \BreakFlag:=errvar;
    IF errvar = ERR_TP_DOBREAK TPWrite "ended by do1";
    ! TPReadNum example: "How many units should be produced?"
    TPReadNum reg1, "How many units should be produced?";
    TPWrite "units: " \Num:=reg1;
    TPReadDnum d, "A big number";
    TPWrite "dnum: " \Dnum:=d;
    ! UIMsgBox example 1: the default button OK.
    UIMsgBox "Continue the program ?";
    ! UIMsgBox example 2: OK/Cancel, the file answers Cancel.
    UIMsgBox \Header:="UIMsgBox Header", "Message Line 1" \MsgLine2:="Message Line 2"
      \Buttons:=btnOKCancel \Icon:=iconInfo \Result:=answer;
    IF answer = resCancel TPWrite "answer = resCancel";
    ! UIMessageBox example: \BtnArray, the answer is the index of the button (Skip -> 2).
    answer := UIMessageBox(\Header:="Cycle step 3" \MsgArray:=my_message
      \BtnArray:=my_buttons \Icon:=iconInfo);
    TPWrite "UIMessageBox: " \Num:=answer;
    ! UINumEntry example: 1..10, integer, the file answers 7.
    n := UINumEntry(\Header:="UINumEntry Header" \Message:="How many units should be produced?"
      \Icon:=iconInfo \InitValue:=5 \MinValue:=1 \MaxValue:=10 \AsInteger);
    TPWrite "UINumEntry: " \Num:=n;
    ! UINumTune example: flow 2.5 in steps of 0.1 within 1.5..3.5, tuned to 2.8.
    n := UINumTune(\Header:="UINumTune Header" \Message:="Tune the flow?" \Icon:=iconInfo,
      2.5, 0.1 \MinValue:=1.5 \MaxValue:=3.5);
    TPWrite "UINumTune: " \Num:=n;
    ! UIAlphaEntry example: the procedure to run, called by late binding.
    s := UIAlphaEntry(\Header:="UIAlphaEntry Header" \Message:="Which procedure do You want to run?"
      \Icon:=iconInfo \InitString:="default_proc");
    %s%;
    ! UIAlphaEntry timing out returns \InitString.
    s := UIAlphaEntry(\Message:="Name?" \InitString:="default_proc" \MaxTime:=5
      \BreakFlag:=errvar);
    TPWrite "UIAlphaEntry: " + s;
    ! UIListView example: item 2 with OK.
    list_item := UIListView(\Result:=button_answer \Header:="UIListView Header", list
      \Buttons:=btnOKCancel \Icon:=iconInfo \DefaultIndex:=1);
    IF button_answer = resOK TPWrite "list item " \Num:=list_item;
    TPShow TP_LATEST;
    ! Without \BreakFlag, a time-out raises ERR_TP_MAXTIME in the ERROR handler.
    TPReadNum reg1, "Quick!" \MaxTime:=1;
    TPWrite "not reached";
  ERROR
    IF ERRNO = ERR_TP_MAXTIME THEN
      TPWrite "handler: ERR_TP_MAXTIME";
      RETURN;
    ENDIF
  ENDPROC

  PROC default_proc()
    TPWrite "default_proc runs";
  ENDPROC

  PROC other_proc()
    TPWrite "other_proc runs";
  ENDPROC
ENDMODULE

module Casing
	var num Total:=0;
	pers BOOL done:=false;
	Local Const num Limit:=3;

	proc Main()
		if Total<Limit then
			Total:=Total+1;
		elseIf total=limit Then
			done:=true;
		Else
			Raise;
		Endif
		WHILE not done do
			done:=TRUE;
		ENDwhile
		for i from 1 to 2 Step 1 do
		endfor
	endproc

	Func num Half(num v)
		Return v/2;
	EndFunc
EndModule

MODULE record_values
  ! Value semantics of records where the interpreter reuses storage: a RETURN hands its
  ! local record to the caller (not a copy), parameters and routine data are set again on
  ! every call from records kept for reuse, and records of other shapes share that pool.
  RECORD cell
    num v;
    pos at;
    string tag;
  ENDRECORD

  VAR cell cells{3};
  VAR pose shared;
  PERS pos kept := [1, 2, 3];

  FUNC cell bumped(cell c)
    VAR cell d;
    d := c;
    d.v := d.v + 1;
    d.at.x := d.at.x + 10;
    RETURN d;
  ENDFUNC

  FUNC cell fresh()
    VAR cell d;
    ! Routine data starts at its default on every call, also after a RETURN handed the
    ! last call's record to the caller.
    Assert d.v = 0;
    Assert d.at = [0, 0, 0];
    Assert d.tag = "";
    d.v := 7;
    d.tag := "seven";
    RETURN d;
  ENDFUNC

  FUNC pos same(pos p)
    RETURN p;
  ENDFUNC

  FUNC pose turned(pose a)
    VAR pose b;
    b := a;
    b.rot := [0, 0, 0, 1];
    RETURN b;
  ENDFUNC

  PROC grow(INOUT cell c)
    c.v := c.v + 100;
    c.at := same(c.at);
  ENDPROC

  PROC test_a_returned_record_is_independent()
    VAR cell a;
    VAR cell b;
    VAR cell first;
    a := [1, [1, 2, 3], "a"];
    b := bumped(a);
    Assert a.v = 1 \Msg:="the argument is a copy";
    Assert a.at.x = 1;
    Assert b.v = 2;
    Assert b.at.x = 11;
    Assert b.tag = "a";
    first := bumped(b);
    b := bumped(first);
    Assert first.v = 3 \Msg:="an earlier result keeps its value after the next call";
    Assert first.at.x = 21;
    Assert b.v = 4;
    b.v := 50;
    Assert first.v = 3;
  ENDPROC

  PROC test_routine_data_starts_at_its_default()
    VAR cell x;
    VAR cell y;
    x := fresh();
    y := fresh();
    x.v := 1;
    Assert y.v = 7;
    Assert y.tag = "seven";
    Assert x.tag = "seven";
  ENDPROC

  PROC test_a_returned_parameter_is_independent()
    VAR pos p := [4, 5, 6];
    VAR pos q;
    q := same(p);
    q.x := 40;
    Assert p.x = 4;
    q := same(same(q));
    Assert q = [40, 5, 6];
  ENDPROC

  PROC test_records_of_other_shapes_in_turn()
    VAR pose a;
    VAR pose b;
    VAR pos p;
    VAR cell c;
    a := [[1, 2, 3], [1, 0, 0, 0]];
    FOR i FROM 1 TO 5 DO
      b := turned(a);
      p := same(b.trans);
      c := bumped([i, p, "x"]);
      shared := turned(b);
    ENDFOR
    Assert a.rot = [1, 0, 0, 0] \Msg:="the argument is a copy";
    Assert b.rot = [0, 0, 0, 1];
    Assert b.trans = [1, 2, 3];
    Assert p = [1, 2, 3];
    Assert c.v = 6;
    Assert c.at = [11, 2, 3];
    Assert shared.trans = [1, 2, 3];
  ENDPROC

  PROC test_array_elements_replaced_by_calls()
    FOR i FROM 1 TO 3 DO
      cells{i} := [i, [i, 0, 0], "c"];
    ENDFOR
    FOR k FROM 1 TO 4 DO
      FOR i FROM 1 TO 3 DO
        cells{i} := bumped(cells{i});
      ENDFOR
    ENDFOR
    Assert cells{1}.v = 5;
    Assert cells{3}.v = 7;
    Assert cells{2}.at.x = 42;
    cells{1} := cells{2};
    cells{2}.v := 0;
    Assert cells{1}.v = 6 \Msg:="assignment copies";
  ENDPROC

  PROC test_inout_and_pers_write_through()
    VAR cell c := [1, [1, 2, 3], "c"];
    grow c;
    Assert c.v = 101;
    Assert c.at = [1, 2, 3];
    kept := same(kept);
    kept.y := 20;
    Assert kept = [1, 20, 3];
    kept := [1, 2, 3];
  ENDPROC
ENDMODULE

MODULE records
  RECORD part
    string name;
    num weight;
    pos at;
  ENDRECORD

  ALIAS num length;

  CONST robtarget home := [[500, 0, 600], [1, 0, 0, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  VAR num grid{2, 3} := [[1, 2, 3], [4, 5, 6]];
  VAR num cube{2, 2, 2};
  VAR part parts{2};

  PROC test_components_at_any_depth()
    VAR robtarget t;
    t := home;
    t.trans.x := t.trans.x + 10;
    Assert t.trans.x = 510;
    Assert home.trans.x = 500 \Msg:="records are copied on assignment";
    Assert t.extax.eax_a = 9E9;
    Assert t.rot.q1 = 1;
  ENDPROC

  PROC test_arrays()
    Assert Dim(grid, 1) = 2;
    Assert Dim(grid, 2) = 3;
    Assert grid{2, 1} = 4;
    grid{1, 3} := 30;
    Assert grid{1, 3} = 30;
    cube{2, 2, 2} := 8;
    Assert cube{2, 2, 2} = 8;
    Assert cube{1, 1, 1} = 0 \Msg:="arrays start at the default value";
    Assert Dim(cube, 3) = 2;
  ENDPROC

  PROC test_out_of_bounds()
    VAR num i := 3;
    grid{i, 1} := 0;
  ERROR
    Assert ERRNO = ERR_OUTOFBND;
  ENDPROC

  PROC test_user_records()
    parts{1} := ["bolt", 0.5, [1, 2, 3]];
    parts{2}.name := "nut";
    parts{2}.at.z := 7;
    Assert parts{1}.name = "bolt";
    Assert parts{2}.at.z = 7;
    Assert parts{2}.weight = 0;
    Assert parts{1} <> parts{2};
    parts{2} := parts{1};
    Assert parts{1} = parts{2} \Msg:="records compare component-wise";
  ENDPROC

  PROC test_alias()
    VAR length l := 3;
    VAR num n;
    n := l * 2;
    Assert n = 6;
  ENDPROC

  PROC test_pos_arithmetic()
    VAR pos a := [1, 2, 3];
    VAR pos b := [4, 5, 6];
    Assert a + b = [5, 7, 9];
    Assert b - a = [3, 3, 3];
    Assert 2 * a = [2, 4, 6];
    Assert a * 2 = [2, 4, 6];
    Assert a * b = [-3, 6, -3] \Msg:="pos * pos is the cross product";
    Assert -a = [-1, -2, -3];
  ENDPROC

  PROC test_orient_product()
    VAR orient q;
    q := OrientZYX(90, 0, 0) * OrientZYX(90, 0, 0);
    Assert Abs(EulerZYX(\Z, q) - 180) < 0.001 OR Abs(EulerZYX(\Z, q) + 180) < 0.001;
  ENDPROC

  PROC test_pose_functions()
    VAR pose p1 := [[100, 0, 0], [1, 0, 0, 0]];
    VAR pose p2;
    VAR pos v;
    p2 := PoseMult(p1, PoseInv(p1));
    Assert Abs(p2.trans.x) < 0.001;
    v := PoseVect(p1, [1, 2, 3]);
    Assert v = [101, 2, 3];
    Assert Distance([0, 0, 0], [3, 4, 0]) = 5;
    Assert VectMagn([0, 3, 4]) = 5;
    Assert DotProd([1, 2, 3], [4, 5, 6]) = 32;
  ENDPROC

  PROC test_offs_and_reltool()
    VAR robtarget t;
    t := Offs(home, 10, 20, 30);
    Assert t.trans = [510, 20, 630];
    Assert t.rot = home.rot;
    t := RelTool(home, 0, 0, 100);
    Assert t.trans.z = 700;
  ENDPROC

  PROC test_norient()
    VAR orient q := [2, 0, 0, 0];
    q := NOrient(q);
    Assert q.q1 = 1;
  ENDPROC
  ! Records are copied on assignment, also when a variable is given a new value of
  ! numbers in place.
  PROC test_record_written_in_place_leaves_copies_alone()
    VAR pos a;
    VAR pos b;
    VAR orient q;
    a := [1, 2, 3];
    b := a;
    a := [4, 5, 6];
    Assert b.x = 1 AND b.y = 2 AND b.z = 3 \Msg:="a copy taken before";
    Assert a.x = 4 AND a.y = 5 AND a.z = 6;
    a := [a.z, a.x, a.y];
    Assert a.x = 6 AND a.y = 4 AND a.z = 5 \Msg:="every component read before any is written";
    b.x := 10;
    Assert a.x = 6;
    q := [1, 0, 0, 0];
    Assert q.q1 = 1 AND q.q4 = 0;
  ENDPROC
ENDMODULE

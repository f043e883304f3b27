MODULE record_math
  ! Arithmetic on components of records held by routine data and parameters, where the
  ! interpreter reads `r.f` and `r.f.g` directly and multiplies two components inline:
  ! the values, and the errors (a missing optional record, a product outside num's
  ! range) with the ERRNO an ERROR handler sees. Also elements of an array of records
  ! replaced by calls, with an index out of bounds.
  RECORD pt
    num x;
    num y;
  ENDRECORD

  RECORD tagged
    num x;
    string name;
  ENDRECORD

  VAR pt pts{3};

  FUNC num dot(pos a, pos b)
    RETURN a.x * b.x + a.y * b.y + a.z * b.z;
  ENDFUNC

  FUNC num lead(pose a, pose b)
    RETURN a.trans.x * b.rot.q1 - a.rot.q4 * b.trans.z + 2 * a.trans.y - b.rot.q2 * 3;
  ENDFUNC

  FUNC num opt_x(\pos p)
    RETURN p.x * 2;
  ENDFUNC

  FUNC num opt_prod(num k, \pos p)
    RETURN k * 1 + p.x * p.y;
  ENDFUNC

  FUNC pt swapped(pt p)
    RETURN [p.y, p.x];
  ENDFUNC

  PROC test_products_of_components()
    VAR pos a := [1, 2, 3];
    VAR pos b := [4, -5, 6];
    VAR pose p := [[10, 20, 30], [0.5, 0.25, 0, 2]];
    VAR pose q := [[1, 2, 7], [3, 4, 0, 0]];
    Assert dot(a, b) = 12;
    Assert dot(b, a) = 12;
    ! 10 * 3 - 2 * 7 + 2 * 20 - 4 * 3
    Assert lead(p, q) = 44;
    Assert a = [1, 2, 3] \Msg:="the arguments are copies";
  ENDPROC

  PROC test_component_of_a_missing_optional_record()
    VAR num r;
    r := opt_x();
    Assert FALSE;
  ERROR
    Assert ERRNO = ERR_NOTPRES;
  ENDPROC

  PROC test_product_with_a_missing_optional_record()
    VAR num r;
    r := opt_prod(1 \p:=[2, 3, 4]);
    Assert r = 7;
    r := opt_prod(1);
    Assert FALSE;
  ERROR
    Assert ERRNO = ERR_NOTPRES;
  ENDPROC

  PROC test_product_outside_the_range_of_num()
    VAR pos a := [1e30, 1e30, 0];
    VAR num r := 0;
    r := dot(a, a);
    Assert FALSE;
  ERROR
    Assert ERRNO = ERR_NUM_LIMIT;
    Assert r = 0;
  ENDPROC

  PROC test_components_of_other_types_beside_numbers()
    VAR tagged t := [3, "three"];
    VAR num r;
    r := t.x * t.x + StrLen(t.name);
    Assert r = 14;
  ENDPROC

  PROC test_array_of_records_replaced_by_calls()
    FOR i FROM 1 TO 3 DO
      pts{i} := [i, 10 * i];
    ENDFOR
    FOR i FROM 1 TO 3 DO
      pts{i} := swapped(pts{i});
    ENDFOR
    Assert pts{1} = [10, 1];
    Assert pts{3} = [30, 3];
    pts{2} := pts{1};
    pts{1}.x := 0;
    Assert pts{2} = [10, 1] \Msg:="assignment copies";
  ENDPROC

  PROC test_array_of_records_index_out_of_bounds()
    VAR num i := 4;
    pts{i} := swapped(pts{1});
    Assert FALSE;
  ERROR
    Assert ERRNO = ERR_OUTOFBND;
  ENDPROC
ENDMODULE

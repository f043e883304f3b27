MODULE array_compare_tests
  ! `=` and `<>` on whole arrays of a value type compare element by element (a real
  ! controller backup does `IF stReact = ["x", "x", "x"] THEN`).
  PERS string names{3} := ["a", "b", "c"];
  VAR num grid{2,2} := [[1, 2], [3, 4]];
  VAR pos points{2} := [[1, 2, 3], [4, 5, 6]];

  PROC test_string_arrays_compare_with_an_aggregate()
    names := ["a", "b", "c"];
    Assert names = ["a", "b", "c"];
    Assert names <> ["a", "b", "d"];
    Assert NOT (names = ["c", "b", "a"]);
  ENDPROC

  PROC test_arrays_compare_element_by_element()
    VAR num other{2,2};
    other := grid;
    Assert other = grid;
    other{2,1} := 30;
    Assert other <> grid;
    Assert grid = [[1, 2], [3, 4]];
  ENDPROC

  PROC test_record_arrays_compare_every_component()
    VAR pos copy{2};
    copy := points;
    Assert copy = points;
    copy{2}.z := 7;
    Assert copy <> points;
  ENDPROC
ENDMODULE

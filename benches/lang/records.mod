MODULE records
  ! Records and arrays of records: 100 particles bounce in a box. Every step replaces each
  ! particle by a moved copy (a FUNC taking and returning a record), and every tenth step a
  ! scan finds the particle with the most bounces. Same algorithm: records.py, records.lua.
  CONST num N := 25000;

  RECORD particle
    num x;
    num y;
    num vx;
    num vy;
    num hits;
  ENDRECORD

  VAR particle ps{100};

  FUNC particle moved(particle p)
    VAR particle q;
    q := p;
    q.x := q.x + q.vx;
    IF q.x < 0 OR q.x > 1000 THEN
      q.vx := -q.vx;
      q.hits := q.hits + 1;
    ENDIF
    q.y := q.y + q.vy;
    IF q.y < 0 OR q.y > 1000 THEN
      q.vy := -q.vy;
      q.hits := q.hits + 1;
    ENDIF
    RETURN q;
  ENDFUNC

  FUNC num busiest()
    VAR num best := 1;
    FOR i FROM 2 TO 100 DO
      IF ps{i}.hits > ps{best}.hits THEN
        best := i;
      ENDIF
    ENDFOR
    RETURN best;
  ENDFUNC

  PROC main()
    VAR num check := 0;
    VAR num hits := 0;
    FOR i FROM 1 TO 100 DO
      ps{i} := [i * 7 MOD 1000, i * 13 MOD 1000, (i MOD 7) * 3 - 9, (i MOD 5) * 4 - 8, 0];
    ENDFOR
    FOR s FROM 1 TO N DO
      FOR i FROM 1 TO 100 DO
        ps{i} := moved(ps{i});
      ENDFOR
      IF s MOD 10 = 0 THEN
        check := (check + busiest() * s) MOD 1000000;
      ENDIF
    ENDFOR
    FOR i FROM 1 TO 100 DO
      hits := hits + ps{i}.hits;
    ENDFOR
    TPWrite "result: " + NumToStr(check, 0) + " " + NumToStr(hits, 0);
  ENDPROC
ENDMODULE

MODULE pose
  ! Pose math on the predefined records: quaternion products, rotating vectors, composing
  ! poses, written as RAPID functions over pos, orient and pose. Same algorithm: pose.py,
  ! pose.lua (tuples and tables there).
  CONST num N := 200000;

  FUNC orient qmul(orient a, orient b)
    RETURN [a.q1 * b.q1 - a.q2 * b.q2 - a.q3 * b.q3 - a.q4 * b.q4,
            a.q1 * b.q2 + a.q2 * b.q1 + a.q3 * b.q4 - a.q4 * b.q3,
            a.q1 * b.q3 - a.q2 * b.q4 + a.q3 * b.q1 + a.q4 * b.q2,
            a.q1 * b.q4 + a.q2 * b.q3 - a.q3 * b.q2 + a.q4 * b.q1];
  ENDFUNC

  FUNC pos cross(pos a, pos b)
    RETURN [a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x];
  ENDFUNC

  FUNC pos rotate(orient q, pos v)
    ! v + 2w(u × v) + 2u × (u × v), u the vector part of q
    VAR pos u;
    VAR pos t;
    VAR pos c;
    u := [q.q2, q.q3, q.q4];
    t := cross(u, v);
    t := [2 * t.x, 2 * t.y, 2 * t.z];
    c := cross(u, t);
    RETURN [v.x + q.q1 * t.x + c.x, v.y + q.q1 * t.y + c.y, v.z + q.q1 * t.z + c.z];
  ENDFUNC

  FUNC pose compose(pose a, pose b)
    VAR pos p;
    p := rotate(a.rot, b.trans);
    RETURN [[a.trans.x + p.x, a.trans.y + p.y, a.trans.z + p.z], qmul(a.rot, b.rot)];
  ENDFUNC

  FUNC orient about_z(num deg)
    RETURN [Cos(deg / 2), 0, 0, Sin(deg / 2)];
  ENDFUNC

  PROC main()
    VAR pose a;
    VAR pose b;
    VAR pose c;
    VAR pos v;
    VAR num check := 0;
    FOR i FROM 1 TO N DO
      a := [[i MOD 100, 0, 50], about_z(i MOD 360)];
      b := [[10, 20, 30], about_z((i * 7) MOD 360)];
      c := compose(a, b);
      v := rotate(c.rot, [100, 0, 0]);
      check := (check + Trunc((v.x + c.trans.x + 1000) / 10)) MOD 100000;
    ENDFOR
    TPWrite "result: " + NumToStr(check, 0);
  ENDPROC
ENDMODULE

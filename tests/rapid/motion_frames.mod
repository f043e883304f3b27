MODULE motion_frames
  ! DefFrame, DefDFrame, MirPos and IsSyncMoveOn. The point layouts follow the RAPID
  ! reference's descriptions (three points: x from the first toward the second, the third in
  ! the xy plane; MirPos mirrors in the xy plane of MirPlane); the expected values are worked
  ! out by hand from those definitions, not copied from a manual.
  CONST robtarget a := [[100, 0, 0], [1, 0, 0, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST robtarget b := [[100, 100, 0], [1, 0, 0, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST robtarget c := [[0, 50, 0], [1, 0, 0, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  PERS wobjdata mirror_xy := [FALSE, TRUE, "", [[0, 0, 0], [1, 0, 0, 0]], [[0, 0, 0], [1, 0, 0, 0]]];
  PERS wobjdata mirror_z100 := [FALSE, TRUE, "", [[0, 0, 100], [1, 0, 0, 0]], [[0, 0, 0], [1, 0, 0, 0]]];
  PERS wobjdata table := [FALSE, TRUE, "", [[500, 0, 0], [1, 0, 0, 0]], [[0, 0, 0], [1, 0, 0, 0]]];

  FUNC bool near(num x, num y)
    RETURN Abs(x - y) < 0.001;
  ENDFUNC

  PROC test_defframe_origin_in_the_first_point()
    VAR pose f;
    f := DefFrame(a, b, c);
    ! x along world +y, y toward world -x, z up: 90 degrees about z.
    Assert near(f.trans.x, 100) AND near(f.trans.y, 0) AND near(f.trans.z, 0);
    Assert near(f.rot.q1, Sqrt(0.5)) AND near(f.rot.q4, Sqrt(0.5));
    Assert near(f.rot.q2, 0) AND near(f.rot.q3, 0);
  ENDPROC

  PROC test_defframe_origin_options()
    VAR pose f;
    f := DefFrame(a, b, c \Origin:=2);
    Assert near(f.trans.y, 100);
    ! Origin 3: on the line through the first two points, with the third on the y axis.
    f := DefFrame(a, b, c \Origin:=3);
    Assert near(f.trans.x, 100) AND near(f.trans.y, 50);
    f := DefFrame(a, b, c \Origin:=1);
    Assert near(f.trans.y, 0);
  ENDPROC

  PROC test_defframe_on_a_line_is_err_frame()
    VAR pose f;
    f := DefFrame(a, b, Offs(b, 0, 100, 0));
    Assert FALSE \Msg:="three points on a line define no frame";
  ERROR
    Assert ERRNO = ERR_FRAME;
  ENDPROC

  PROC test_defdframe_maps_old_points_onto_new_ones()
    VAR pose d;
    VAR pos p;
    ! The three points turned 90 degrees about z and moved by [10, 20, 0].
    d := DefDFrame(a, b, c, Offs(a, -90, 120, 0), Offs(b, -190, 20, 0), Offs(c, -40, -30, 0));
    Assert near(d.rot.q1, Sqrt(0.5)) AND near(d.rot.q4, Sqrt(0.5));
    Assert near(d.trans.x, 10) AND near(d.trans.y, 20) AND near(d.trans.z, 0);
    p := PoseVect(d, c.trans);
    Assert near(p.x, -40) AND near(p.y, 20);
  ENDPROC

  PROC test_mirpos_in_the_world_xy_plane()
    VAR robtarget m;
    ! A tool pointing down ([0, 0, 1, 0]): mirrored in z, its x and z axes are mirrored
    ! and y completes the frame: 180 degrees about z.
    m := MirPos([[100, 200, 300], [0, 0, 1, 0], [1, 0, 1, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]], mirror_xy);
    Assert near(m.trans.x, 100) AND near(m.trans.y, 200) AND near(m.trans.z, -300);
    Assert near(Abs(m.rot.q4), 1);
    Assert m.robconf.cf1 = 1 AND m.robconf.cfx = 0 \Msg:="the configuration is kept";
    ! \MirY: y and z mirrored, x completes the frame: 180 degrees about y for tool0's axes.
    m := MirPos([[100, 200, 300], [1, 0, 0, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]], mirror_xy \MirY);
    Assert near(Abs(m.rot.q3), 1);
    m := MirPos([[100, 200, 300], [1, 0, 0, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]], mirror_xy);
    Assert near(Abs(m.rot.q2), 1);
  ENDPROC

  PROC test_mirpos_with_a_plane_and_a_work_object()
    VAR robtarget m;
    ! The plane z = 100 of the world; the point given in a work object 500 mm along x.
    m := MirPos([[0, 0, 150], [1, 0, 0, 0], [0, 0, 0, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]], mirror_z100 \WObj:=table);
    Assert near(m.trans.x, 0) AND near(m.trans.z, 50);
  ENDPROC

  PROC test_no_synchronized_movement()
    Assert NOT IsSyncMoveOn();
  ENDPROC
ENDMODULE

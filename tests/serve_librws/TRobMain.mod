MODULE TRobMain
    ! The state a StateMachine add-in keeps where abb_egm_rws_managers reads it (its own
    ! RAPID, written for this test): with this module loaded, `rw/system` lists the add-in.
    PERS num current_state := 1;
ENDMODULE

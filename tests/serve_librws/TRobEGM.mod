MODULE TRobEGM
    ! The EGM action a StateMachine add-in keeps where abb_egm_rws_managers reads it.
    PERS num current_action := 3;
ENDMODULE

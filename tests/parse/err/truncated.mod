MODULE Cut
  PROC main()
    MoveL [[100, 200, 300], [1, 0, 0, 0], [0, 0, 0, 0], [9E9, 9E9

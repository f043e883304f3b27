MODULE files
  ! The controller's file system on real files (a fresh HOME: per `rapidvc test`). Each test
  ! works in its own directory and removes it. Where a test follows an example of the RAPID
  ! reference manual (Instructions, Functions), the comment names it.
  VAR iodev logfile;
  VAR iodev infile;
  VAR errnum last_err := 0;

  ! Remove a test directory and the files in it (one level).
  PROC clean(string path)
    VAR dir d;
    VAR string name;
    IF NOT IsFile(path \Directory) RETURN;
    OpenDir d, path;
    WHILE ReadDir(d, name) DO
      IF name <> "." AND name <> ".." THEN
        RemoveFile path + "/" + name;
      ENDIF
    ENDWHILE
    CloseDir d;
    RemoveDir path;
  ENDPROC

  ! Open: "Open "HOME:" \File:= "LOGFILE1.DOC", logfile \Write;" then Write "Execution
  ! started" and "No of produced parts=" \Num:=reg1 (Write's example).
  PROC test_open_write_read_text()
    VAR num reg1 := 5;
    VAR string text;
    clean "HOME:/t_text";
    MakeDir "HOME:/t_text";
    Open "HOME:/t_text" \File:="LOGFILE1.DOC", logfile \Write;
    Write logfile, "Execution started";
    Write logfile, "No of produced parts=" \Num:=reg1;
    Write logfile, "flag " \Bool:=TRUE;
    Write logfile, "" \Pos:=[1, 2, 3];
    Write logfile, "no newline" \NoNewLine;
    Close logfile;
    Open diskhome \File:="t_text/LOGFILE1.DOC", infile \Read;
    text := ReadStr(infile);
    Assert text = "Execution started";
    Assert ReadStr(infile) = "No of produced parts=5";
    Assert ReadStr(infile) = "flag TRUE";
    Assert ReadStr(infile) = "[1,2,3]";
    Assert ReadStr(infile) = "no newline";
    Assert ReadStr(infile) = "EOF" \Msg:="ReadStr gives EOF at the end of the file";
    Close infile;
    clean "HOME:/t_text";
  ENDPROC

  ! \Append adds to the end; \Write replaces the whole file.
  PROC test_append_and_replace()
    clean "HOME:/t_app";
    MakeDir "HOME:/t_app";
    Open "HOME:/t_app/a.txt", logfile \Write;
    Write logfile, "one";
    Close logfile;
    Open "HOME:/t_app/a.txt", logfile \Append;
    Write logfile, "two";
    Close logfile;
    Open "HOME:/t_app/a.txt", logfile;
    Write logfile, "three";
    Close logfile;
    Open "HOME:/t_app/a.txt", infile \Read;
    Assert ReadStr(infile) = "one";
    Assert ReadStr(infile) = "two";
    Assert ReadStr(infile) = "three" \Msg:="no switch appends, as with Append";
    Close infile;
    Open "HOME:/t_app/a.txt", logfile \Write;
    Write logfile, "new";
    Close logfile;
    Assert FileSize("HOME:/t_app/a.txt") = 4;
    clean "HOME:/t_app";
  ENDPROC

  ! ReadStr's \Delim, \RemoveCR and \DiscardHeaders; ReadNum and EOF_NUM (ReadNum's example:
  ! "reg1 := ReadNum(infile);").
  PROC test_read_options()
    VAR num reg1;
    clean "HOME:/t_rd";
    MakeDir "HOME:/t_rd";
    Open "HOME:/t_rd/f.txt", logfile \Write;
    Write logfile, "a b  c\0D";
    Write logfile, "12.5";
    Write logfile, " -3 ";
    Close logfile;
    Open "HOME:/t_rd/f.txt", infile \Read;
    Assert ReadStr(infile \Delim:=" ") = "a";
    Assert ReadStr(infile \Delim:=" " \DiscardHeaders) = "b";
    Assert ReadStr(infile \RemoveCR \DiscardHeaders \Delim:=" \0A") = "c";
    reg1 := ReadNum(infile);
    Assert reg1 = 12.5;
    Assert ReadNum(infile) = -3;
    Assert ReadNum(infile) = EOF_NUM;
    Assert ReadNum(infile) = 9.998E36;
    Close infile;
    clean "HOME:/t_rd";
  ENDPROC

  PROC test_readnum_not_a_number()
    last_err := 0;
    clean "HOME:/t_nan";
    MakeDir "HOME:/t_nan";
    Open "HOME:/t_nan/f.txt", logfile \Write;
    Write logfile, "abc";
    Close logfile;
    Open "HOME:/t_nan/f.txt", infile \Read;
    IF ReadNum(infile) = 0 THEN
    ENDIF
    Assert last_err = ERR_RCVDATA;
    Close infile;
    clean "HOME:/t_nan";
  ERROR
    last_err := ERRNO;
    TRYNEXT;
  ENDPROC

  ! A line longer than 80 characters comes back in pieces of at most 80.
  PROC test_readstr_80_characters()
    VAR string s40 := "0123456789012345678901234567890123456789";
    clean "HOME:/t_long";
    MakeDir "HOME:/t_long";
    Open "HOME:/t_long/f.txt", logfile \Write;
    Write logfile, s40 \NoNewLine;
    Write logfile, s40 \NoNewLine;
    Write logfile, "xyz";
    Close logfile;
    Open "HOME:/t_long/f.txt", infile \Read;
    Assert StrLen(ReadStr(infile)) = 80;
    Assert ReadStr(infile) = "xyz";
    Close infile;
    clean "HOME:/t_long";
  ENDPROC

  ! WriteBin's example: "out_buffer{1} := 5; WriteBin channel2, out_buffer, 1;"; ReadBin's
  ! example reads bytes until EOF_BIN; WriteStrBin/ReadStrBin ("text := ReadStrBin
  ! (channel2, 10);").
  PROC test_binary_bytes_and_strings()
    VAR num out_buffer{3} := [5, 0, 255];
    VAR num character;
    VAR num n := 0;
    VAR num sum := 0;
    clean "HOME:/t_bin";
    MakeDir "HOME:/t_bin";
    Open "HOME:/t_bin/b.bin", logfile \Write \Bin;
    WriteBin logfile, out_buffer, 3;
    WriteStrBin logfile, "Hello world";
    Close logfile;
    Assert FileSize("HOME:/t_bin/b.bin") = 14;
    Open "HOME:/t_bin/b.bin", infile \Read \Bin;
    Assert ReadBin(infile) = 5;
    Assert ReadBin(infile) = 0;
    Assert ReadBin(infile) = 255;
    Assert ReadStrBin(infile, 5) = "Hello";
    Assert ReadStrBin(infile, 10) = " world" \Msg:="fewer characters at the end";
    Assert ReadStrBin(infile, 10) = "EOF";
    Rewind infile;
    character := ReadBin(infile);
    WHILE character <> EOF_BIN DO
      n := n + 1;
      sum := sum + character;
      character := ReadBin(infile);
    ENDWHILE
    Assert n = 14;
    Assert ReadBin(infile) = -1;
    Close infile;
    clean "HOME:/t_bin";
  ENDPROC

  ! WriteAnyBin/ReadAnyBin's example sends a robtarget; a value comes back bit for bit.
  PROC test_any_bin_round_trip()
    VAR robtarget cur_robt := [[600.123, -12.5, 1E-7], [0.7071068, 0, 0.7071068, 0], [0, -1, 2, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
    VAR robtarget next_target;
    VAR string s := "quote ""q"" and \\ done";
    VAR string s2;
    VAR dnum big := 4294967295;
    VAR dnum big2;
    clean "HOME:/t_any";
    MakeDir "HOME:/t_any";
    Open "HOME:/t_any/d.bin", logfile \Write \Bin;
    WriteAnyBin logfile, cur_robt;
    WriteAnyBin logfile, s;
    WriteAnyBin logfile, big;
    Close logfile;
    Open "HOME:/t_any/d.bin", infile \Read \Bin;
    ReadAnyBin infile, next_target;
    Assert next_target = cur_robt;
    ReadAnyBin infile, s2;
    Assert s2 = s;
    ReadAnyBin infile, big2;
    Assert big2 = big;
    last_err := 0;
    ReadAnyBin infile, big2;
    Assert last_err = ERR_RANYBIN_EOF;
    Close infile;
    clean "HOME:/t_any";
  ERROR
    last_err := ERRNO;
    TRYNEXT;
  ENDPROC

  ! Binary data that WriteAnyBin did not write, or of another type, is ERR_RANYBIN_CHK.
  PROC test_any_bin_check()
    VAR num n;
    last_err := 0;
    clean "HOME:/t_chk";
    MakeDir "HOME:/t_chk";
    Open "HOME:/t_chk/d.bin", logfile \Write \Bin;
    WriteAnyBin logfile, "text";
    WriteStrBin logfile, "garbage";
    Close logfile;
    Open "HOME:/t_chk/d.bin", infile \Read \Bin;
    ReadAnyBin infile, n;
    Assert last_err = ERR_RANYBIN_CHK \Msg:="a string read into a num";
    last_err := 0;
    ReadAnyBin infile, n;
    Assert last_err = ERR_RANYBIN_CHK \Msg:="bytes not written by WriteAnyBin";
    Close infile;
    clean "HOME:/t_chk";
  ERROR
    last_err := ERRNO;
    TRYNEXT;
  ENDPROC

  ! \Bin alone opens for reading and writing at the end of the file.
  PROC test_bin_read_write()
    VAR num b{1} := [7];
    clean "HOME:/t_rw";
    MakeDir "HOME:/t_rw";
    Open "HOME:/t_rw/x.bin", logfile \Bin;
    Assert ReadBin(logfile) = EOF_BIN;
    WriteBin logfile, b, 1;
    Rewind logfile;
    Assert ReadBin(logfile) = 7;
    ClearIOBuff logfile;
    Close logfile;
    clean "HOME:/t_rw";
  ENDPROC

  ! MakeDir, IsFile (its example: "IsFile("HOME:/mydir" \Directory)"), RenameFile
  ! ("RenameFile "HOME:/myfile", "HOME:/yourfile";"), CopyFile, FileSize, RemoveFile.
  PROC test_files_and_directories()
    VAR dir directory;
    VAR string filename;
    VAR num count := 0;
    clean "HOME:/mydir";
    Assert NOT IsFile("HOME:/mydir");
    MakeDir "HOME:/mydir";
    Assert IsFile("HOME:/mydir" \Directory);
    Assert NOT IsFile("HOME:/mydir" \RegularFile);
    Open "HOME:/mydir/myfile", logfile \Write;
    Write logfile, "12345";
    Close logfile;
    Assert IsFile("HOME:/mydir/myfile");
    Assert IsFile("HOME:/mydir/myfile" \RegularFile);
    Assert NOT IsFile("HOME:/mydir/myfile" \Directory);
    Assert FileSize("HOME:/mydir/myfile") = 6;
    RenameFile "HOME:/mydir/myfile", "HOME:/mydir/yourfile";
    Assert NOT IsFile("HOME:/mydir/myfile");
    CopyFile "HOME:/mydir/yourfile", "$HOME/mydir/copy";
    Assert FileSize("HOME:/mydir/copy") = 6;
    OpenDir directory, "HOME:/mydir";
    WHILE ReadDir(directory, filename) DO
      count := count + 1;
      IF count = 1 Assert filename = ".";
      IF count = 2 Assert filename = "..";
      IF count = 3 Assert filename = "copy" \Msg:="names in order";
      IF count = 4 Assert filename = "yourfile";
    ENDWHILE
    CloseDir directory;
    Assert count = 4;
    RemoveFile "HOME:/mydir/yourfile";
    RemoveFile "HOME:/mydir/copy";
    RemoveDir "HOME:/mydir";
    Assert NOT IsFile("HOME:/mydir");
  ENDPROC

  ! RenameFile and CopyFile never overwrite: ERR_FILEEXIST.
  PROC test_no_overwrite()
    last_err := 0;
    clean "HOME:/t_ex";
    MakeDir "HOME:/t_ex";
    Open "HOME:/t_ex/a", logfile \Write;
    Close logfile;
    Open "HOME:/t_ex/b", logfile \Write;
    Close logfile;
    RenameFile "HOME:/t_ex/a", "HOME:/t_ex/b";
    Assert last_err = ERR_FILEEXIST;
    last_err := 0;
    CopyFile "HOME:/t_ex/a", "HOME:/t_ex/b";
    Assert last_err = ERR_FILEEXIST;
    Assert IsFile("HOME:/t_ex/a");
    clean "HOME:/t_ex";
  ERROR
    last_err := ERRNO;
    TRYNEXT;
  ENDPROC

  ! Errors as the manual lists them: a file that cannot be opened is ERR_FILEOPEN, every
  ! other access error ERR_FILEACC, and no path leaves the controller's storage.
  PROC test_errors()
    last_err := 0;
    Open "HOME:/no/such/dir/f.txt", infile \Read;
    Assert last_err = ERR_FILEOPEN;
    last_err := 0;
    Open "HOME:/../escape.txt", infile \Write;
    Assert last_err = ERR_FILEOPEN \Msg:="`..` is refused";
    last_err := 0;
    Open "/etc/passwd", infile \Read;
    Assert last_err = ERR_FILEOPEN \Msg:="a host path is refused";
    last_err := 0;
    RemoveFile "HOME:/no_such_file";
    Assert last_err = ERR_FILEACC;
    last_err := 0;
    Assert FileSize("$HOME/../x") = 0;
    Assert last_err = ERR_FILEACC;
    last_err := 0;
    MakeDir "TEMP:/../../x";
    Assert last_err = ERR_FILEACC;
    last_err := 0;
    Write infile, "never opened";
    Assert last_err = ERR_FILEACC;
    last_err := 0;
    RemoveDir "HOME:/no_such_dir";
    Assert last_err = ERR_FILEACC;
  ERROR
    last_err := ERRNO;
    TRYNEXT;
  ENDPROC

  ! Reading a file opened for writing, or opening an iodev twice, is an error.
  PROC test_wrong_direction()
    last_err := 0;
    clean "HOME:/t_dir";
    MakeDir "HOME:/t_dir";
    Open "HOME:/t_dir/w", logfile \Write;
    Assert ReadStr(logfile) = "";
    Assert last_err = ERR_FILEACC;
    last_err := 0;
    Open "HOME:/t_dir/w2", logfile \Write;
    Assert last_err = ERR_FILEOPEN;
    Close logfile;
    Close logfile;
    clean "HOME:/t_dir";
  ERROR
    last_err := ERRNO;
    TRYNEXT;
  ENDPROC

  ! TEMP: and RAMDISK: are roots too; diskram names RAMDISK:.
  PROC test_other_roots()
    Open disktemp \File:="t.txt", logfile \Write;
    Write logfile, "temp";
    Close logfile;
    Assert IsFile("$TEMP/t.txt");
    RemoveFile "TEMP:/t.txt";
    Open diskram \File:="r.txt", logfile \Write;
    Close logfile;
    Assert IsFile("RAMDISK:/r.txt");
    RemoveFile "$RAMDISK/r.txt";
  ENDPROC

  ! FileTime's and FSSize's examples ("FSSize("HOME:/spy.log" \Total)").
  PROC test_times_and_sizes()
    VAR num total;
    VAR num free;
    clean "HOME:/t_fs";
    MakeDir "HOME:/t_fs";
    Open "HOME:/t_fs/spy.log", logfile \Write;
    Close logfile;
    Assert FileTime("HOME:/t_fs/spy.log") > 1.6E9 \Msg:="seconds since 1970";
    Assert FileTime("HOME:/t_fs/spy.log" \ModifyTime) > 1.6E9;
    Assert FileTime("HOME:/t_fs/spy.log" \AccessTime) > 1.6E9;
    Assert FileTime("HOME:/t_fs/spy.log" \StatCTime) > 1.6E9;
    total := FSSize("HOME:/t_fs/spy.log" \Total);
    free := FSSize("HOME:/t_fs/spy.log" \Free);
    Assert total > 0;
    Assert free <= total;
    Assert FSSize("HOME:/t_fs/spy.log" \Total \Kbyte) <= total / 1000;
    clean "HOME:/t_fs";
  ENDPROC

  ! ModExist checks whether a module of that name is in the task (system modules too);
  ! names compare without regard to case.
  PROC test_mod_exist()
    Assert ModExist("files");
    Assert ModExist("FILES");
    Assert ModExist("BASE") \Msg:="system modules count";
    Assert NOT ModExist("mymod");
  ENDPROC
ENDMODULE

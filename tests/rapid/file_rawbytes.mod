MODULE file_rawbytes
  ! WriteRawBytes and ReadRawBytes on a binary file of HOME: (a fresh one per rapidvc test).
  VAR iodev io;

  ! WriteRawBytes' example: "PackRawBytes … raw_data_out; … WriteRawBytes io_device,
  ! raw_data_out;" then ReadRawBytes reads it back from the file.
  PROC test_write_read_raw_bytes()
    VAR rawbytes out;
    VAR rawbytes in;
    VAR num x;
    VAR string s;
    PackRawBytes 1234.5, out, 1 \Float4;
    PackRawBytes "abc", out, RawBytesLen(out) + 1 \ASCII;
    Open "HOME:/raw.bin", io \Write \Bin;
    WriteRawBytes io, out;
    WriteRawBytes io, out \NoOfBytes:=4;
    Close io;
    Assert FileSize("HOME:/raw.bin") = 11;
    Open "HOME:/raw.bin", io \Read \Bin;
    ReadRawBytes io, in, 7;
    Assert RawBytesLen(in) = 7;
    UnpackRawBytes in, 1, x \Float4;
    UnpackRawBytes in, 5, s \ASCII:=3;
    Assert x = 1234.5 AND s = "abc";
    ! Fewer bytes than asked: what is there.
    ReadRawBytes io, in, 100 \Time:=1;
    Assert RawBytesLen(in) = 4;
    Close io;
    RemoveFile "HOME:/raw.bin";
  ENDPROC

  ! The end of the file is ERR_RANYBIN_EOF; NoOfBytes outside 1 … 1024 ERR_ARGVALERR.
  PROC test_read_raw_bytes_errors()
    VAR errnum err := 0;
    VAR rawbytes in;
    Open "HOME:/empty.bin", io \Write \Bin;
    Close io;
    Open "HOME:/empty.bin", io \Read \Bin;
    ReadRawBytes io, in, 1;
    Assert err = ERR_RANYBIN_EOF;
    err := 0;
    ReadRawBytes io, in, 1025;
    Assert err = ERR_ARGVALERR;
    Close io;
    RemoveFile "HOME:/empty.bin";
  ERROR
    err := ERRNO;
    TRYNEXT;
  ENDPROC
ENDMODULE

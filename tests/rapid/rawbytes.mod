MODULE rawbytes_tests
  ! rawbytes and its instructions (PackRawBytes, UnpackRawBytes, CopyRawBytes,
  ! ClearRawBytes, RawBytesLen). The values are those of the examples of ABB's "RAPID
  ! Instructions, Functions and Data types" manual; where an example packs a DeviceNet header
  ! first (PackDNHeader, which needs a DeviceNet bus), the data start at index 1 instead.

  RECORD msg
    num kind;
    rawbytes data;
  ENDRECORD

  VAR num caught := 0;

  ! The single bytes of raw from index `first` on, as text ("8 0 0 0").
  FUNC string bytes_of(VAR rawbytes raw, num first, num count)
    VAR string s := "";
    VAR byte b;
    FOR i FROM first TO first + count - 1 DO
      UnpackRawBytes raw, i, b \Hex1;
      IF s <> "" s := s + " ";
      s := s + NumToStr(b, 0);
    ENDFOR
    RETURN s;
  ENDFUNC

  PROC test_a_new_rawbytes_is_empty()
    ! rawbytes data type: the valid length of a fresh container is 0.
    VAR rawbytes raw;
    Assert RawBytesLen(raw) = 0;
  ENDPROC

  PROC test_packrawbytes_examples()
    ! PackRawBytes, examples 1-7, each packed after the valid bytes (RawBytesLen + 1).
    VAR rawbytes raw_data;
    VAR num integer := 8;
    VAR dnum bigInt := 4294967295;
    VAR num float := 13.4;
    VAR byte data1 := 122;
    VAR byte byte1;
    VAR string string1 := "abcdefg";
    VAR dnum d;
    VAR num f;
    VAR string s;
    ! Example 1: the next 4 bytes hold 8 (DINT, little-endian without \Network).
    PackRawBytes integer, raw_data, (RawBytesLen(raw_data) + 1) \IntX:=DINT;
    Assert RawBytesLen(raw_data) = 4;
    Assert bytes_of(raw_data, 1, 4) = "8 0 0 0";
    ! Example 2: the next 4 bytes hold 4294967295 (UDINT).
    PackRawBytes bigInt, raw_data, (RawBytesLen(raw_data) + 1) \IntX:=UDINT;
    Assert RawBytesLen(raw_data) = 8;
    Assert bytes_of(raw_data, 5, 4) = "255 255 255 255";
    UnpackRawBytes raw_data, 5, d \IntX:=UDINT;
    Assert d = 4294967295;
    ! Example 3: the next 8 bytes hold 4294967295 (LINT).
    PackRawBytes bigInt, raw_data, (RawBytesLen(raw_data) + 1) \IntX:=LINT;
    Assert RawBytesLen(raw_data) = 16;
    Assert bytes_of(raw_data, 9, 8) = "255 255 255 255 0 0 0 0";
    ! Example 4: the next 4 bytes hold 13.4 (\Float4).
    PackRawBytes float, raw_data, (RawBytesLen(raw_data) + 1) \Float4;
    UnpackRawBytes raw_data, 17, f \Float4;
    Assert f = 13.4;
    ! Example 5: the next byte is 122, the ASCII code of "z".
    PackRawBytes data1, raw_data, (RawBytesLen(raw_data) + 1) \ASCII;
    UnpackRawBytes raw_data, 21, s \ASCII:=1;
    Assert s = "z";
    ! Example 6: the next 7 bytes are "abcdefg".
    PackRawBytes string1, raw_data, (RawBytesLen(raw_data) + 1) \ASCII;
    UnpackRawBytes raw_data, 22, s \ASCII:=7;
    Assert s = "abcdefg";
    ! Example 7: byte1 := StrToByte("1F" \Hex); the next byte is 1F hexadecimal.
    byte1 := StrToByte("1F" \Hex);
    PackRawBytes byte1, raw_data, (RawBytesLen(raw_data) + 1) \Hex1;
    Assert RawBytesLen(raw_data) = 29;
    Assert bytes_of(raw_data, 29, 1) = "31";
  ENDPROC

  PROC test_unpackrawbytes_example()
    ! UnpackRawBytes example: integer (DINT) at 1, float at 5, a 10-character string at 9,
    ! a byte (\Hex1) at 19 and one character into a byte (\ASCII:=1) at 20.
    VAR rawbytes raw_data_in;
    VAR num integer;
    VAR num float;
    VAR string string1;
    VAR byte byte1;
    VAR byte data1;
    PackRawBytes 5, raw_data_in, 1 \IntX:=DINT;
    PackRawBytes 13.4, raw_data_in, 5 \Float4;
    PackRawBytes "abcdefghij", raw_data_in, 9 \ASCII;
    PackRawBytes 31, raw_data_in, 19 \Hex1;
    PackRawBytes 122, raw_data_in, 20 \ASCII;
    Assert RawBytesLen(raw_data_in) = 20;
    UnpackRawBytes raw_data_in, 1, integer \IntX:=DINT;
    UnpackRawBytes raw_data_in, 5, float \Float4;
    UnpackRawBytes raw_data_in, 9, string1 \ASCII:=10;
    UnpackRawBytes raw_data_in, 19, byte1 \Hex1;
    UnpackRawBytes raw_data_in, 20, data1 \ASCII:=1;
    Assert integer = 5;
    Assert float = 13.4;
    Assert string1 = "abcdefghij";
    Assert byte1 = 31;
    Assert data1 = 122;
  ENDPROC

  PROC test_network_order_is_big_endian()
    ! \Network: ProfiBus and InterBus order (big-endian) for \IntX and \Float4.
    VAR rawbytes raw;
    VAR num n;
    VAR num f;
    PackRawBytes 258, raw \Network, 1 \IntX:=DINT;
    Assert bytes_of(raw, 1, 4) = "0 0 1 2";
    UnpackRawBytes raw \Network, 1, n \IntX:=DINT;
    Assert n = 258;
    ! Without \Network the same bytes are another number.
    UnpackRawBytes raw, 1, n \IntX:=DINT;
    Assert n = 33619968;
    PackRawBytes -2.5, raw \Network, 5 \Float4;
    Assert bytes_of(raw, 5, 4) = "192 32 0 0";
    UnpackRawBytes raw \Network, 5, f \Float4;
    Assert f = -2.5;
    PackRawBytes -2, raw \Network, 9 \IntX:=INT;
    Assert bytes_of(raw, 9, 2) = "255 254";
    UnpackRawBytes raw \Network, 9, n \IntX:=INT;
    Assert n = -2;
    UnpackRawBytes raw \Network, 9, n \IntX:=UINT;
    Assert n = 65534;
    PackRawBytes -128, raw, 11 \IntX:=SINT;
    UnpackRawBytes raw, 11, n \IntX:=USINT;
    Assert n = 128;
    Assert RawBytesLen(raw) = 11;
  ENDPROC

  PROC test_copyrawbytes_example()
    ! CopyRawBytes example: integer and float copied to index 3 of to_raw_data.
    VAR rawbytes from_raw_data;
    VAR rawbytes to_raw_data;
    VAR num integer := 8;
    VAR num float := 13.4;
    VAR num n;
    VAR num f;
    ClearRawBytes from_raw_data;
    PackRawBytes integer, from_raw_data, 1 \IntX:=DINT;
    PackRawBytes float, from_raw_data, (RawBytesLen(from_raw_data) + 1) \Float4;
    CopyRawBytes from_raw_data, 1, to_raw_data, 3 \NoOfBytes:=RawBytesLen(from_raw_data);
    Assert RawBytesLen(to_raw_data) = 10;
    Assert bytes_of(to_raw_data, 1, 2) = "0 0";
    UnpackRawBytes to_raw_data, 3, n \IntX:=DINT;
    UnpackRawBytes to_raw_data, 7, f \Float4;
    Assert n = 8;
    Assert f = 13.4;
    ! Without \NoOfBytes: every valid byte from FromIndex on.
    CopyRawBytes from_raw_data, 5, to_raw_data, 1;
    UnpackRawBytes to_raw_data, 1, f \Float4;
    Assert f = 13.4;
    Assert RawBytesLen(to_raw_data) = 10;
  ENDPROC

  PROC test_clearrawbytes_example()
    ! ClearRawBytes example: \FromIndex:=5 clears the float and leaves 4 valid bytes.
    VAR rawbytes raw_data;
    VAR num integer := 8;
    VAR num float := 13.4;
    PackRawBytes integer, raw_data, 1 \IntX:=DINT;
    PackRawBytes float, raw_data, (RawBytesLen(raw_data) + 1) \Float4;
    Assert RawBytesLen(raw_data) = 8;
    ClearRawBytes raw_data \FromIndex:=5;
    Assert RawBytesLen(raw_data) = 4;
    Assert bytes_of(raw_data, 1, 4) = "8 0 0 0";
    ClearRawBytes raw_data;
    Assert RawBytesLen(raw_data) = 0;
  ENDPROC

  PROC test_rawbyteslen_example()
    ! RawBytesLen example: the length grows with every pack after the valid bytes.
    VAR rawbytes raw_data;
    PackRawBytes 8, raw_data, (RawBytesLen(raw_data) + 1) \IntX:=DINT;
    PackRawBytes 13.4, raw_data, (RawBytesLen(raw_data) + 1) \Float4;
    Assert RawBytesLen(raw_data) = 8;
    ! Packing inside the valid bytes leaves the length.
    PackRawBytes 1, raw_data, 2 \IntX:=USINT;
    Assert RawBytesLen(raw_data) = 8;
    ! Packing beyond them pads with zeros.
    PackRawBytes 1, raw_data, 20 \IntX:=USINT;
    Assert RawBytesLen(raw_data) = 20;
    Assert bytes_of(raw_data, 9, 2) = "0 0";
  ENDPROC

  PROC test_a_rawbytes_in_a_record()
    ! As message buffers are kept: a record with a rawbytes component, copied with it.
    VAR msg m1;
    VAR msg m2;
    VAR num n;
    m1.kind := 10;
    PackRawBytes 1234, m1.data, 1 \IntX:=DINT;
    m2 := m1;
    UnpackRawBytes m2.data, 1, n \IntX:=DINT;
    Assert n = 1234;
    Assert RawBytesLen(m2.data) = 4;
  ENDPROC

  PROC pack_at(num index)
    VAR rawbytes raw;
    PackRawBytes 1, raw, index \IntX:=DINT;
  ERROR
    caught := ERRNO;
    TRYNEXT;
  ENDPROC

  PROC test_indexes_outside_the_container_are_err_outofbnd()
    VAR rawbytes raw;
    VAR num n;
    caught := 0;
    pack_at 1022;
    Assert caught = ERR_OUTOFBND \Msg:="4 bytes from 1022 end beyond 1024";
    caught := 0;
    pack_at 0;
    Assert caught = ERR_OUTOFBND;
    caught := 0;
    pack_at 1021;
    Assert caught = 0;
    ! Reading past the valid bytes.
    PackRawBytes 7, raw, 1 \IntX:=UINT;
    caught := 0;
    UnpackRawBytes raw, 1, n \IntX:=DINT;
    Assert caught = ERR_OUTOFBND \Msg:="unpacking 4 of 2 valid bytes must fail";
    Assert n = 0;
  ERROR
    caught := ERRNO;
    TRYNEXT;
  ENDPROC

  PROC test_values_outside_their_format_are_err_argvalerr()
    VAR rawbytes raw;
    VAR num n;
    VAR dnum big := 4294967295;
    caught := 0;
    PackRawBytes 256, raw, 1 \IntX:=USINT;
    Assert caught = ERR_ARGVALERR;
    caught := 0;
    PackRawBytes 1.5, raw, 1 \IntX:=DINT;
    Assert caught = ERR_ARGVALERR;
    caught := 0;
    PackRawBytes -1, raw, 1 \IntX:=UDINT;
    Assert caught = ERR_ARGVALERR;
    caught := 0;
    PackRawBytes 300, raw, 1 \Hex1;
    Assert caught = ERR_ARGVALERR;
    ! A UDINT beyond 2^24 does not fit a num exactly: unpack it into a dnum.
    caught := 0;
    PackRawBytes big, raw, 1 \IntX:=UDINT;
    Assert caught = 0;
    UnpackRawBytes raw, 1, n \IntX:=UDINT;
    Assert caught = ERR_ARGVALERR;
    Assert RawBytesLen(raw) = 4;
  ERROR
    caught := ERRNO;
    TRYNEXT;
  ENDPROC
ENDMODULE

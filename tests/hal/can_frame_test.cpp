// CanFrame: DLC↔length mapping, validity rules, padding, and can-utils text notation.
#include <gtest/gtest.h>

#include "hal/can_frame.hpp"
#include "hal/host/can_text.hpp"

using namespace curio::hal;

TEST(CanFrame, DlcMapsToTheFdLengths) {
  const uint8_t expected[16] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 12, 16, 20, 24, 32, 48, 64};
  for (uint8_t dlc = 0; dlc < 16; ++dlc) {
    EXPECT_EQ(dlc_to_len(dlc), expected[dlc]);
    EXPECT_EQ(len_to_dlc(expected[dlc]), dlc) << "exact lengths map back";
  }
  EXPECT_EQ(dlc_to_len(16), 0xFF);
}

TEST(CanFrame, LengthsBetweenFdSizesRoundUp) {
  EXPECT_EQ(len_to_dlc(9), 9);
  EXPECT_EQ(fd_padded_len(9), 12);
  EXPECT_EQ(fd_padded_len(13), 16);
  EXPECT_EQ(fd_padded_len(33), 48);
  EXPECT_EQ(fd_padded_len(49), 64);
  EXPECT_EQ(fd_padded_len(65), 0xFF);
  EXPECT_TRUE(is_valid_len(48, true));
  EXPECT_FALSE(is_valid_len(47, true));
  EXPECT_FALSE(is_valid_len(12, false));
  EXPECT_TRUE(is_valid_len(8, false));
}

TEST(CanFrame, ValidityChecksIdWidthLengthAndFlags) {
  CanFrame f;
  f.id = 0x7FF;
  f.len = 8;
  EXPECT_TRUE(is_valid(f));
  f.id = 0x800;
  EXPECT_FALSE(is_valid(f)) << "11-bit id overflow";
  f.flags = kFlagExtended;
  EXPECT_TRUE(is_valid(f));
  f.id = 0x20000000;
  EXPECT_FALSE(is_valid(f)) << "29-bit id overflow";
  f = CanFrame{};
  f.len = 12;
  EXPECT_FALSE(is_valid(f)) << "classic frames hold at most 8 bytes";
  f.flags = kFlagFd;
  EXPECT_TRUE(is_valid(f));
  f.flags = kFlagFd | kFlagRemote;
  EXPECT_FALSE(is_valid(f)) << "FD has no remote frames";
  f = CanFrame{};
  f.flags = kFlagBrs;
  EXPECT_FALSE(is_valid(f)) << "BRS only on FD";
  f.flags = 0x80;
  EXPECT_FALSE(is_valid(f)) << "unknown flag bits";
}

TEST(CanFrame, MakeFramePadsFdPayloads) {
  const uint8_t payload[10] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
  CanFrame f;
  ASSERT_TRUE(make_frame(&f, 0x123, false, true, payload, 10, 0xCC));
  EXPECT_EQ(f.len, 12);
  EXPECT_EQ(f.data[9], 10);
  EXPECT_EQ(f.data[10], 0xCC);
  EXPECT_EQ(f.data[11], 0xCC);
  EXPECT_TRUE(f.fd());
  EXPECT_TRUE(is_valid(f));
  EXPECT_FALSE(make_frame(&f, 0x123, false, false, payload, 9)) << "9 bytes need FD";
  EXPECT_FALSE(make_frame(&f, 0x800, false, false, payload, 1)) << "id too wide";
  EXPECT_EQ(f.len, 12) << "failed make_frame leaves the frame alone";
}

TEST(CanText, RoundTripsCanUtilsNotation) {
  for (const char* text : {"123#DEADBEEF", "1FFFFFFF#00", "123#", "123#R",
                           "18DAF120##1"
                           "000102030405060708090A0B",
                           "7FF##0", "100##3AA"}) {
    CanFrame f;
    ASSERT_TRUE(parse_frame(text, &f)) << text;
    EXPECT_EQ(format_frame(f), text);
  }
  CanFrame f;
  ASSERT_TRUE(parse_frame("123#DE.AD.BE.EF", &f));
  EXPECT_EQ(f.len, 4);
  EXPECT_EQ(f.data[3], 0xEF);
}

TEST(CanText, RejectsMalformedText) {
  CanFrame f;
  for (const char* text :
       {"", "123", "12#00", "800#00", "123#0", "123#GG", "123#001122334455667788",
        "123##1001122334455667788", "123##4", "1234#00"}) {
    EXPECT_FALSE(parse_frame(text, &f)) << text;
  }
}

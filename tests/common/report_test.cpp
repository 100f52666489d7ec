// Plain-text reports (common/report.hpp): the columns of Table::text() line up (text left,
// numbers right, a rule as wide as the table), CSV quoting, and the number formats.
#include "huygens/common/report.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <sstream>
#include <string>
#include <vector>

using namespace huygens;

namespace {

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

}  // namespace

TEST(Table, ColumnsLineUp) {
  Table t({"case", "measured", "result"});
  t.add({"fft", "2.25e-07", "pass"});
  t.add({"cauchy_poisson", "1", "FAIL"});
  t.add({"x", "-0.000123", "pass"});
  const auto lines = lines_of(t.text());
  ASSERT_EQ(lines.size(), 5u);  // header, rule, three rows
  // widths 14 ("cauchy_poisson"), 9 ("-0.000123"), 6 ("result"), two blanks between columns;
  // the header and text are left-aligned, numbers right-aligned, the last column unpadded
  EXPECT_EQ(lines[0], "case            measured   result");
  EXPECT_EQ(lines[1], std::string(14 + 2 + 9 + 2 + 6, '-'));
  EXPECT_EQ(lines[2], "fft              2.25e-07  pass");
  EXPECT_EQ(lines[3], "cauchy_poisson          1  FAIL");
  EXPECT_EQ(lines[4], "x               -0.000123  pass");
  // every number ends, and every text of the last column starts, at the same position
  for (std::size_t r = 2; r < lines.size(); ++r) {
    EXPECT_EQ(lines[r].find_last_not_of(' ', 24), 24u) << lines[r];
    EXPECT_EQ(lines[r].find_first_not_of(' ', 25), 27u) << lines[r];
  }
}

// A short row is padded with empty cells; the last column carries no trailing blanks.
TEST(Table, ShortRowsAndNoTrailingBlanks) {
  Table t({"a", "bb"});
  t.add({"long text"});
  const auto lines = lines_of(t.text());
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0], "a          bb");
  EXPECT_EQ(lines[2], "long text  ");  // the separator, then the empty last cell unpadded
  EXPECT_EQ(t.rows().size(), 1u);
}

TEST(Table, CsvQuotesOnlyWhatNeedsIt) {
  Table t({"name", "value"});
  t.add({"plain", "1.5"});
  t.add({"a, b", "say \"hi\""});
  EXPECT_EQ(t.csv(), "name,value\nplain,1.5\n\"a, b\",\"say \"\"hi\"\"\"\n");
}

TEST(Report, NumberFormats) {
  EXPECT_EQ(num(1.2345678), "1.235");
  EXPECT_EQ(num(0.5, 3), "0.5");
  EXPECT_EQ(num(1.5e-5), "1.500e-05");
  EXPECT_EQ(num(2.5e7, 2), "2.5e+07");
  EXPECT_EQ(num(0.0), "0");
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(num(inf), "inf");
  EXPECT_EQ(num(-inf), "-inf");
  EXPECT_EQ(num(std::numeric_limits<double>::quiet_NaN()), "nan");
  EXPECT_EQ(fmt("%d-%s-%.2f", 7, "x", 0.125), "7-x-0.12");
}

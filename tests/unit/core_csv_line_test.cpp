// The one CSV line splitter (metrics tables, design files, particle files): cells, their columns for
// file:line:column messages, quoting as RFC 4180 has it.
#include <gtest/gtest.h>

#include <stdexcept>

#include "core/csv_line.hpp"

namespace sm = spreadmap;

TEST(CoreCsvLine, CellsAreTrimmedAndKeepTheColumnWhereTheyStart) {
  const auto cells = sm::core::split_csv_line("x, y ,\tz,,radius ", "f.csv:2");
  ASSERT_EQ(cells.size(), 5u);
  EXPECT_EQ(cells[0].text, "x");
  EXPECT_EQ(cells[0].column, 1u);
  EXPECT_EQ(cells[1].text, "y");
  EXPECT_EQ(cells[1].column, 4u);  // after the blank that follows the comma
  EXPECT_EQ(cells[2].text, "z");
  EXPECT_EQ(cells[2].column, 8u);  // after the tab
  EXPECT_EQ(cells[3].text, "");    // an empty cell is kept
  EXPECT_EQ(cells[3].column, 10u);
  EXPECT_EQ(cells[4].text, "radius");
  EXPECT_EQ(sm::core::split_csv_line("", "f.csv:3").size(), 1u);
  EXPECT_EQ(sm::core::split_csv_line("a,", "f.csv:3").back().text, "");
}

TEST(CoreCsvLine, QuotedCellsHoldCommasAndDoubledQuotes) {
  const auto cells = sm::core::split_csv_line(R"(1,"a, ""b""",  "c" ,2)", "f.csv:1");
  ASSERT_EQ(cells.size(), 4u);
  EXPECT_EQ(cells[1].text, R"(a, "b")");
  EXPECT_EQ(cells[1].column, 3u);
  EXPECT_EQ(cells[2].text, "c");
  EXPECT_EQ(cells[3].text, "2");
}

TEST(CoreCsvLine, AnUnterminatedQuoteNamesTheLineAndColumn) {
  try {
    sm::core::split_csv_line(R"(1,2, "open)", "metrics.csv:7");
    FAIL() << "an unterminated quote was accepted";
  } catch (const std::runtime_error &e) {
    EXPECT_STREQ(e.what(), "metrics.csv:7:6: unterminated quoted field");
  }
}

// "Did you mean": edit distance (case-insensitive) and the closest candidate within a distance that
// grows with the word, so that typos are caught and unrelated words are not "corrected".
#include <gtest/gtest.h>

#include "core/suggest.hpp"

namespace sm = spreadmap;

TEST(CoreSuggest, EditDistanceIsLevenshteinIgnoringCase) {
  EXPECT_EQ(sm::edit_distance("", ""), 0u);
  EXPECT_EQ(sm::edit_distance("abc", ""), 3u);
  EXPECT_EQ(sm::edit_distance("kitten", "sitting"), 3u);
  EXPECT_EQ(sm::edit_distance("Roller", "roller"), 0u);
  EXPECT_EQ(sm::edit_distance("diamter", "diameter"), 1u);
  EXPECT_EQ(sm::edit_distance("omega", "omgea"), 2u);  // a transposition costs two edits
  EXPECT_EQ(sm::edit_distance("abc", "xyz"), sm::edit_distance("xyz", "abc"));
}

TEST(CoreSuggest, ClosestPicksTheNearestCandidate) {
  const std::vector<std::string> stages = {"simulate", "characterise", "train", "map"};
  EXPECT_EQ(sm::closest("simulat", stages), "simulate");
  EXPECT_EQ(sm::closest("characterize", stages), "characterise");
  EXPECT_EQ(sm::closest("MAP", stages), "map");
  EXPECT_EQ(sm::closest("trian", stages), "train");
  const std::vector<std::string> laws = {"hertz_mindlin", "hooke_history", "hooke_slider"};
  EXPECT_EQ(sm::closest("hooke_slidr", laws), "hooke_slider");
  EXPECT_EQ(sm::closest("hooke_histroy", laws), "hooke_history");
}

TEST(CoreSuggest, NothingCloseMeansNoSuggestion) {
  const std::vector<std::string> stages = {"simulate", "characterise", "train", "map"};
  EXPECT_EQ(sm::closest("banana", stages), "");
  EXPECT_EQ(sm::closest("x", {}), "");
  EXPECT_EQ(sm::closest("zzzzzzzzzzzz", {"diameter", "density"}), "");
}

TEST(CoreSuggest, JoinLowerIequals) {
  EXPECT_EQ(sm::join({"a", "b", "c"}), "a, b, c");
  EXPECT_EQ(sm::join({"a", "b"}, "|"), "a|b");
  EXPECT_EQ(sm::join({}), "");
  EXPECT_EQ(sm::lower("Vs_RQ"), "vs_rq");
  EXPECT_TRUE(sm::iequals("Omega", "oMEGA"));
  EXPECT_FALSE(sm::iequals("omega", "omegas"));
}

TEST(CoreSuggest, SplitKeepsEveryItemEmptyOnesToo) {
  using V = std::vector<std::string>;
  EXPECT_EQ(sm::split("40, 70,100 mm/s", ','), (V{"40", " 70", "100 mm/s"}));
  EXPECT_EQ(sm::split("a||b|", '|'), (V{"a", "", "b", ""}));
  EXPECT_EQ(sm::split("", ','), (V{""}));
  EXPECT_EQ(sm::join(sm::split("x,y,z", ','), ","), "x,y,z");
}

// Schema lint for every contact plugin: the params[] table is the user's reference manual
// (`spreadmap plugins contact NAME`), so each entry must be well formed.
#include <gtest/gtest.h>

#include <cmath>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "verification/contact_laws.hpp"

namespace sm = spreadmap;

namespace {

template <class Law> class ContactSchema : public ::testing::Test {};
TYPED_TEST_SUITE(ContactSchema, sm::test::ContactLaws::Types);

bool nonempty(const char *s) { return s && *s; }

TYPED_TEST(ContactSchema, EveryEntryIsWellFormed) {
  const std::regex snake("[a-z][a-z0-9]*(_[a-z0-9]+)*");
  std::set<std::string> names;
  for (const sm_param_v1 &p : TypeParam::params) {
    SCOPED_TRACE(p.name ? p.name : "(null name)");
    ASSERT_TRUE(nonempty(p.name));
    EXPECT_TRUE(std::regex_match(p.name, snake)) << "names are full-word snake_case";
    EXPECT_GE(std::string(p.name).size(), 4u) << "full words, not symbols";
    EXPECT_TRUE(names.insert(p.name).second) << "duplicate name";
    EXPECT_TRUE(nonempty(p.unit));
    ASSERT_TRUE(nonempty(p.doc));
    EXPECT_EQ(std::string(p.doc).find('\n'), std::string::npos) << "doc is one line";
    if (p.type == SM_NUMBER || p.type == SM_INTEGER) {
      EXPECT_TRUE(std::isfinite(p.min) && std::isfinite(p.max)) << "finite range";
      EXPECT_LT(p.min, p.max);
      if (!p.required) {
        EXPECT_GE(p.def, p.min);
        EXPECT_LE(p.def, p.max);
      }
    }
    if (p.type == SM_BOOLEAN) {
      EXPECT_TRUE(p.def == 0 || p.def == 1);
    }
    if (p.type == SM_ENUM) {
      ASSERT_TRUE(nonempty(p.choices) && nonempty(p.def_text));
      std::set<std::string> choices;
      std::stringstream in(p.choices);
      for (std::string c; std::getline(in, c, '|');) {
        EXPECT_TRUE(std::regex_match(c, snake)) << c;
        choices.insert(c);
      }
      EXPECT_TRUE(choices.count(p.def_text)) << "default '" << p.def_text << "' is one of the choices";
    }
  }
  EXPECT_FALSE(names.empty());
}

}  // namespace

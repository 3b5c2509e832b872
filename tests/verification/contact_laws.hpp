// The in-tree contact laws, listed once for every test that runs the same checks over each of them:
// typed suites take ContactLaws::Types, suites over the built plugins ContactLaws::names(). A new law
// is added here (its header, its plugin name, its place in the list) and nowhere else.
#pragma once
#include <gtest/gtest.h>

#include <vector>

#include "plugins/contact/hertz_mindlin/hertz_mindlin.hpp"
#include "plugins/contact/hooke_history/hooke_history.hpp"
#include "plugins/contact/hooke_slider/hooke_slider.hpp"

namespace spreadmap::test {

// The name a law registers as a plugin (its folder under plugins/contact/).
template <class Law> inline constexpr const char *contact_law_name = nullptr;
template <> inline constexpr const char *contact_law_name<HookeSlider> = "hooke_slider";
template <> inline constexpr const char *contact_law_name<HookeHistory> = "hooke_history";
template <> inline constexpr const char *contact_law_name<HertzMindlin> = "hertz_mindlin";

template <class... Law> struct ContactLawList {
  static_assert(((contact_law_name<Law> != nullptr) && ...), "every listed law needs its contact_law_name");
  using Types = ::testing::Types<Law...>;
  static std::vector<const char *> names() { return {contact_law_name<Law>...}; }
};

using ContactLaws = ContactLawList<HookeSlider, HookeHistory, HertzMindlin>;

}  // namespace spreadmap::test

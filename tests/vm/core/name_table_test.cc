#include "vm/core/name_table.h"

#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "vm/cli/choice_option.h"

namespace vs11 {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

enum class Fruit { kApple, kPear, kQuince };

constexpr NameTable kFruitNames("fruit", {Choice(Fruit::kApple, "apple"), Choice(Fruit::kPear, "pear", "a soft one"),
                                          Choice(Fruit::kQuince, "quince", "cooked only")});

// Built at compile time: a wrong row or lookup would not compile.
static_assert(kFruitNames.Find("pear") == Fruit::kPear);
static_assert(!kFruitNames.Find("Pear"));
static_assert(kFruitNames.Name(Fruit::kQuince) == "quince");
static_assert(kFruitNames.size() == 3);

TEST(NameTable, ParsesEveryNameAndNamesEveryValue) {
  for (const NamedChoice<Fruit>& choice : kFruitNames) {
    EXPECT_EQ(kFruitNames.Parse(choice.name), choice.value);
    EXPECT_EQ(kFruitNames.Name(choice.value), choice.name);
  }
  EXPECT_THAT(kFruitNames.Names(), ElementsAre("apple", "pear", "quince"));
}

TEST(NameTable, UnknownNameErrorListsTheValidNames) {
  EXPECT_EQ(kFruitNames.UnknownName("fig"), "unknown fruit 'fig' (use apple, pear or quince)");
  EXPECT_EQ(kFruitNames.UnknownName("fig", "any"), "unknown fruit 'fig' (use any, apple, pear or quince)");
  try {
    kFruitNames.Parse("fig");
    FAIL() << "an unknown name parsed";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "unknown fruit 'fig' (use apple, pear or quince)");
  }
}

TEST(NameTable, HelpListsNamesWithTheirDescriptions) {
  EXPECT_EQ(kFruitNames.Help(), "apple, pear (a soft one) or quince (cooked only)");
  EXPECT_EQ(kFruitNames.List(), "apple, pear or quince");
}

TEST(NameTable, RejectsARepeatedName) {
  EXPECT_THROW(NameTable("fruit", {Choice(Fruit::kApple, "apple"), Choice(Fruit::kPear, "apple")}), std::logic_error);
  EXPECT_THROW(NameTable("fruit", {Choice(Fruit::kApple, "")}), std::logic_error);
}

// The command line parses the flag into the enum; an unknown name is a usage error listing the names.
TEST(ChoiceOption, ParsesIntoTheEnumAndRejectsUnknownNamesWithTheList) {
  Fruit fruit = Fruit::kApple;
  std::optional<Fruit> maybe;
  std::vector<Fruit> basket;
  auto make_app = [&] {
    auto app = std::make_unique<CLI::App>();
    cli::AddChoiceOption(*app, "--fruit", fruit, kFruitNames, "the fruit");
    cli::AddChoiceOption(*app, "--maybe", maybe, kFruitNames, "any", "a fruit or any");
    cli::AddChoiceListOption(*app, "--basket", basket, kFruitNames, "fruits");
    return app;
  };
  {
    auto app = make_app();
    EXPECT_THAT(app->help(), HasSubstr("apple"));  // the default, by name
    app->parse(std::vector<std::string>{"pear,quince", "--basket", "any", "--maybe", "quince", "--fruit"});  // reversed
    EXPECT_EQ(fruit, Fruit::kQuince);
    EXPECT_EQ(maybe, std::nullopt);
    EXPECT_THAT(basket, ElementsAre(Fruit::kPear, Fruit::kQuince));
  }
  {
    auto app = make_app();
    app->parse(std::vector<std::string>{"pear", "--maybe"});
    EXPECT_EQ(maybe, Fruit::kPear);
  }
  for (const char* flag : {"--fruit", "--maybe", "--basket"}) {
    auto app = make_app();
    try {
      app->parse(std::vector<std::string>{"fig", flag});
      FAIL() << flag << " accepted an unknown name";
    } catch (const CLI::ValidationError& e) {
      EXPECT_THAT(e.what(), HasSubstr("unknown fruit 'fig' (use ")) << flag;
      EXPECT_THAT(e.what(), HasSubstr("apple, pear or quince)")) << flag;
    }
  }
}

}  // namespace
}  // namespace vs11

// The writers' number formatting (libdla/io/output_file.h) against the standard library: the
// fast paths must give the bytes the plain calls give.
#include "io/output_file.h"

#include <gtest/gtest.h>

#include <atomic>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <future>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using dla::detail::Text;

template <class Write>
std::string text_of(Write&& write) {
  Text text;
  write(text);
  return std::string(text.view());
}

// fixed() is llround, then the integer and fraction digits with trailing zeros dropped.
std::string fixed_reference(double value, int decimals) {
  const long long units = std::llround(value * std::pow(10.0, decimals));
  const unsigned long long magnitude = static_cast<unsigned long long>(std::llabs(units));
  const unsigned long long scale = static_cast<unsigned long long>(std::llround(std::pow(10.0, decimals)));
  std::string out = (units < 0 ? "-" : "") + std::to_string(magnitude / scale);
  if (decimals == 0) return out;
  std::string fraction = std::to_string(magnitude % scale);
  fraction.insert(0, static_cast<std::size_t>(decimals) - fraction.size(), '0');
  while (!fraction.empty() && fraction.back() == '0') fraction.pop_back();
  return fraction.empty() ? out : out + "." + fraction;
}

TEST(Text, FixedRoundsAsLlroundDoes) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-12, 9), places(0, 9);
  // Halfway cases and their neighbours, where a hand-written rounding goes wrong first.
  for (const double value : {0.5, -0.5, 1.5, -2.5, 0.49999999999999994, -0.49999999999999994, 2.0005, 0.0, -0.0,
                             1e-12, 123456.7895, std::nextafter(0.5, 0.0), std::nextafter(-1.5, 0.0)})
    for (int d = 0; d <= 9; ++d)
      ASSERT_EQ(text_of([&](Text& t) { t.fixed(value, d); }), fixed_reference(value, d)) << value << " " << d;
  for (int i = 0; i < 200000; ++i) {
    const int d = places(random);
    const double value = mantissa(random) * std::pow(10.0, std::min(exponent(random), 8 - d));
    ASSERT_EQ(text_of([&](Text& t) { t.fixed(value, d); }), fixed_reference(value, d)) << value << " " << d;
  }
}

TEST(Text, NumbersReadBackExactly) {
  std::mt19937_64 random(8);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-40, 40);
  for (int i = 0; i < 100000; ++i) {
    const double value = mantissa(random) * std::pow(10.0, exponent(random));
    const std::string as_double = text_of([&](Text& t) { t.number(value); });
    const std::string as_float = text_of([&](Text& t) { t.float_number(static_cast<float>(value)); });
    double double_back = 0.0;
    float float_back = 0.0f;
    std::from_chars(as_double.data(), as_double.data() + as_double.size(), double_back);
    std::from_chars(as_float.data(), as_float.data() + as_float.size(), float_back);
    ASSERT_EQ(double_back, value) << as_double;
    ASSERT_EQ(float_back, static_cast<float>(value)) << as_float;
    ASSERT_LE(as_float.size(), as_double.size());
  }
}

// The writers' threads: every one finishes, and the first failure is the one thrown.
TEST(FinishAll, WaitsForEveryTaskThenThrowsTheFirstFailure) {
  std::atomic<int> finished{0};
  const auto tasks = [&](int failing_from) {
    std::vector<std::future<void>> started;
    for (int i = 0; i < 4; ++i)
      started.push_back(std::async(std::launch::async, [&finished, i, failing_from] {
        ++finished;
        if (i >= failing_from) throw std::runtime_error("task " + std::to_string(i));
      }));
    return started;
  };
  auto fine = tasks(4);
  EXPECT_NO_THROW(dla::detail::finish_all(fine));
  EXPECT_EQ(finished.load(), 4);

  finished = 0;
  auto failing = tasks(1);
  try {
    dla::detail::finish_all(failing);
    ADD_FAILURE() << "no failure thrown";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "task 1");
  }
  EXPECT_EQ(finished.load(), 4);
  for (const std::future<void>& task : failing) EXPECT_FALSE(task.valid()) << "a task not waited for";

  // This thread's own failure comes first.
  finished = 0;
  auto after_own = tasks(0);
  try {
    dla::detail::finish_all(after_own, std::make_exception_ptr(std::runtime_error("own")));
    ADD_FAILURE() << "no failure thrown";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "own");
  }
  EXPECT_EQ(finished.load(), 4);
}

}  // namespace

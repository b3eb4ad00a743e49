// The by-name integrator registry.
#include <gtest/gtest.h>

#include <map>

#include "jellysim/ode/integrator.hpp"

namespace jellysim::ode {
namespace {

TEST(Registry, NamesAreListedInPresentationOrder) {
  const std::vector<std::string> expected{"forward-euler", "predictor-corrector", "leapfrog", "rk2", "rk4",
                                          "dopri5",        "backward-euler"};
  EXPECT_EQ(integrator_names(), expected);
}

TEST(Registry, EveryNameRoundTripsWithItsOrders) {
  // name -> {order, embedded order}
  const std::map<std::string, std::pair<int, int>> orders{{"forward-euler", {1, 0}}, {"predictor-corrector", {1, 0}},
                                                          {"leapfrog", {2, 0}},      {"rk2", {2, 1}},
                                                          {"rk4", {4, 0}},           {"dopri5", {5, 4}},
                                                          {"backward-euler", {1, 0}}};
  for (const std::string& name : integrator_names()) {
    const auto integrator = make_integrator(name);
    EXPECT_EQ(integrator->name(), name);
    EXPECT_EQ(integrator->order(), orders.at(name).first) << name;
    EXPECT_EQ(integrator->embedded_order(), orders.at(name).second) << name;
    EXPECT_EQ(integrator->has_embedded_pair(), orders.at(name).second > 0) << name;
  }
}

TEST(Registry, UnknownNameThrowsListingTheAllowedNames) {
  try {
    make_integrator("rk45");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("rk45"), std::string::npos) << message;
    for (const std::string& name : integrator_names()) EXPECT_NE(message.find(name), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace jellysim::ode

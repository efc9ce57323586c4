// Live tuning by name: every parameter of cfg/BoWG.cfg reaches exactly its
// own option, and the values in force go back to the client. Fails when a
// cfg parameter is not wired to the detector's options.
#include "bowg_ros/live_parameters.h"

#include <gtest/gtest.h>

#include <string>

#include "bowg/core/errors.h"
#include "bowg_ros/BoWGConfig.h"

namespace bowg_ros {
namespace {

// Another valid value of the cfg parameter `name` in `msg` (its minimum, or
// its maximum when the default is the minimum; booleans flipped); returns it
// as the table's text.
std::string changeValue(const std::string& name, dynamic_reconfigure::Config* msg) {
  dynamic_reconfigure::Config lo, hi;
  BoWGConfig::__getMin__().__toMessage__(lo);
  BoWGConfig::__getMax__().__toMessage__(hi);
  for (std::size_t i = 0; i < msg->bools.size(); ++i) {
    if (msg->bools[i].name != name) continue;
    msg->bools[i].value = !msg->bools[i].value;
    return msg->bools[i].value ? "true" : "false";
  }
  for (std::size_t i = 0; i < msg->ints.size(); ++i) {
    if (msg->ints[i].name != name) continue;
    int& v = msg->ints[i].value;
    v = v != lo.ints[i].value ? lo.ints[i].value : hi.ints[i].value;
    return std::to_string(v);
  }
  for (std::size_t i = 0; i < msg->doubles.size(); ++i) {
    if (msg->doubles[i].name != name) continue;
    double& v = msg->doubles[i].value;
    v = v != lo.doubles[i].value ? lo.doubles[i].value : hi.doubles[i].value;
    return bowg::getParameter(name, [&] {
      bowg::PipelineOptions o;
      bowg::setParameter(name, v, &o);
      return o;
    }());
  }
  ADD_FAILURE() << name << " is not a bool, int or double of the cfg";
  return "";
}

TEST(LiveParameters, EveryCfgParameterChangesExactlyItsOwnOption) {
  const auto descriptions = BoWGConfig::__getParamDescriptions__();
  ASSERT_GE(descriptions.size(), 10u);
  for (const auto& d : descriptions) {
    SCOPED_TRACE(d->name);
    dynamic_reconfigure::Config msg;
    BoWGConfig::__getDefault__().__toMessage__(msg);
    const std::string value = changeValue(d->name, &msg);
    const bowg::PipelineOptions before;
    bowg::PipelineOptions after = before;
    applyLiveConfig(msg, &after);
    for (const bowg::ParameterInfo& p : bowg::parameterTable()) {
      const std::string was = bowg::getParameter(p.name, before);
      const std::string now = bowg::getParameter(p.name, after);
      if (p.name == d->name) {
        EXPECT_NE(now, was) << "setting " << d->name << " changed nothing";
        EXPECT_EQ(now, value);
      } else {
        EXPECT_EQ(now, was) << "setting " << d->name << " changed " << p.name;
      }
    }
  }
}

TEST(LiveParameters, TheValuesInForceGoBackToTheClient) {
  bowg::PipelineOptions options;
  options.detector.similarity.lambda_1 = 0.25;
  options.detector.geometric.min_inliers = 33;
  options.detector.word_groups.enabled = false;
  dynamic_reconfigure::Config msg;
  BoWGConfig::__getDefault__().__toMessage__(msg);
  writeLiveConfig(options, &msg);
  BoWGConfig config;
  config.__fromMessage__(msg);
  EXPECT_EQ(config.lambda_1, 0.25);
  EXPECT_EQ(config.min_inliers, 33);
  EXPECT_FALSE(config.word_groups);
  // And read back, they give the same options.
  bowg::PipelineOptions again;
  applyLiveConfig(msg, &again);
  EXPECT_EQ(again.detector.similarity.lambda_1, 0.25);
  EXPECT_EQ(again.detector.geometric.min_inliers, 33);
  EXPECT_FALSE(again.detector.word_groups.enabled);
}

TEST(LiveParameters, UnknownNamesAndOutOfRangeValuesAreRefusedByName) {
  dynamic_reconfigure::Config msg;
  dynamic_reconfigure::DoubleParameter p;
  p.name = "lamda_1";
  p.value = 0.5;
  msg.doubles.push_back(p);
  bowg::PipelineOptions options;
  try {
    applyLiveConfig(msg, &options);
    ADD_FAILURE() << "unknown name accepted";
  } catch (const bowg::InvalidParameter& e) {
    EXPECT_NE(std::string(e.what()).find("lamda_1"), std::string::npos) << e.what();
  }
  msg.doubles[0].name = "lambda_1";
  msg.doubles[0].value = 1.5;
  EXPECT_THROW(applyLiveConfig(msg, &options), bowg::InvalidParameter);
}

}  // namespace
}  // namespace bowg_ros

// Live tuning by name: every parameter of cfg/BoWG.cfg reaches exactly its
// own option, and the values in force go back to the client. Fails when a
// cfg parameter is not wired to the detector's options.
#include "bowg_ros/live_parameters.h"

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

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
  // Initialised: the generated __fromMessage__ reads each field before it
  // sets it (UBSan reports an indeterminate bool otherwise).
  BoWGConfig config = BoWGConfig::__getDefault__();
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

TEST(LiveParameters, TheDescriptionListsEveryStartOnlyParameterWithItsValueInForce) {
  bowg::PipelineOptions options;
  options.features.orb_levels = 5;
  const dynamic_reconfigure::ConfigDescription d = describeWithStartOnly(options);
  const dynamic_reconfigure::Group* start_only = nullptr;
  for (const dynamic_reconfigure::Group& g : d.groups) {
    if (g.name == "start_only") start_only = &g;
  }
  ASSERT_NE(start_only, nullptr);
  EXPECT_EQ(start_only->parent, 0);
  std::size_t expected = 0;
  for (const bowg::ParameterInfo& p : bowg::parameterTable()) expected += p.live ? 0 : 1;
  ASSERT_EQ(start_only->parameters.size(), expected);
  for (const dynamic_reconfigure::ParamDescription& p : start_only->parameters) {
    const bowg::ParameterInfo* info = bowg::findParameter(p.name);
    ASSERT_NE(info, nullptr) << p.name;
    EXPECT_FALSE(info->live) << p.name;
  }
  // orb_levels: an int whose default, minimum and maximum are the 5 in force.
  for (const dynamic_reconfigure::Config* c : {&d.dflt, &d.min, &d.max}) {
    bool found = false;
    for (const dynamic_reconfigure::IntParameter& p : c->ints) {
      if (p.name != "orb_levels") continue;
      EXPECT_EQ(p.value, 5);
      found = true;
    }
    EXPECT_TRUE(found);
  }
  // Every group id is distinct (clients build a tree by id).
  std::set<int> ids;
  for (const dynamic_reconfigure::Group& g : d.groups) EXPECT_TRUE(ids.insert(g.id).second);
}

TEST(LiveParameters, AStartOnlyChangeIsNamedAndNotApplied) {
  bowg::PipelineOptions options;
  dynamic_reconfigure::Config request;
  dynamic_reconfigure::IntParameter levels;
  levels.name = "orb_levels";
  levels.value = options.features.orb_levels;
  request.ints.push_back(levels);
  // The value in force: nothing to report.
  EXPECT_TRUE(startOnlyRequests(request, options).empty());
  // Another value: one message naming it, its value in force kept.
  request.ints[0].value = options.features.orb_levels + 1;
  const std::vector<std::string> m = startOnlyRequests(request, options);
  ASSERT_EQ(m.size(), 1u);
  EXPECT_NE(m[0].find("orb_levels is start-only"), std::string::npos) << m[0];
  EXPECT_NE(m[0].find(std::to_string(options.features.orb_levels) + " stays in force"),
            std::string::npos)
      << m[0];
  bowg::PipelineOptions after = options;
  applyLiveConfig(request, &after);
  EXPECT_EQ(after.features.orb_levels, options.features.orb_levels);
  // A double given as the client sends it, and a string.
  dynamic_reconfigure::Config other;
  dynamic_reconfigure::DoubleParameter scale;
  scale.name = "orb_scale_factor";
  scale.value = options.features.orb_scale_factor;
  other.doubles.push_back(scale);
  dynamic_reconfigure::StrParameter mask;
  mask.name = "mask_path";
  mask.value = "/tmp/mask.png";
  other.strs.push_back(mask);
  const std::vector<std::string> m2 = startOnlyRequests(other, options);
  ASSERT_EQ(m2.size(), 1u);
  EXPECT_EQ(m2[0].find("mask_path is start-only"), 0u) << m2[0];
  EXPECT_NO_THROW(applyLiveConfig(other, &after));
  // A live parameter is no start-only change.
  dynamic_reconfigure::Config live;
  dynamic_reconfigure::DoubleParameter score;
  score.name = "min_score";
  score.value = 0.9;
  live.doubles.push_back(score);
  EXPECT_TRUE(startOnlyRequests(live, options).empty());
}

TEST(LiveParameters, AnOutOfRangeValueIsRefusedNamingTheRange) {
  dynamic_reconfigure::Config request;
  dynamic_reconfigure::DoubleParameter score;
  score.name = "min_score";
  score.value = 99.0;
  request.doubles.push_back(score);
  bowg::PipelineOptions options;
  try {
    applyLiveConfig(request, &options);
    ADD_FAILURE() << "min_score 99 accepted";
  } catch (const bowg::InvalidParameter& e) {
    EXPECT_NE(std::string(e.what()).find("min_score: 99 is outside [0, 10]"), std::string::npos)
        << e.what();
  }
}

TEST(LiveParameters, TheLiveConfigCarriesTheCfgParametersOnly) {
  bowg::PipelineOptions options;
  options.detector.islands.min_score = 0.7;
  dynamic_reconfigure::Config msg = liveConfig(options);
  BoWGConfig config = BoWGConfig::__getDefault__();  // read before set (see above)
  EXPECT_TRUE(config.__fromMessage__(msg));  // a typed client reads it without complaint
  EXPECT_EQ(config.min_score, 0.7);
}

}  // namespace
}  // namespace bowg_ros

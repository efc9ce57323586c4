// End-to-end tests of LoopDetectorNodelet's live tuning and persistence
// (dynamic_reconfigure and dynparam, the database services, saving at
// shutdown and loading at start); the harness is nodelet_harness.h and
// main() is loop_detector_rostest.cpp's (one test executable).
#include <set>
#include <utility>

#include "nodelet_harness.h"

namespace bowg_ros {
namespace {

// The steps of one scenario (below): each depends on the state the previous
// one left, and the database must survive every change for the last step.

// Each live parameter is in force from the next keyframe; `c` keeps them for
// the next step.
void expectEveryParameterInForceNextKeyframe(Detector& d, const cv::Mat& world, BoWGConfig* cp) {
  BoWGConfig& c = *cp;
  c = BoWGConfig::__getDefault__();
  c.lambda_1 = 0.65;
  c.lambda_2 = 0.25;
  c.w_max = 0.4;
  c.alpha = 0.3;
  c.fan_bins = 12;
  c.min_score = 0.25;
  c.temporal_k = 2;
  c.min_inliers = 20;
  c.direct_index_level = 2;
  c.word_groups = false;
  c.distribution = true;
  c.temporal_score = false;
  c.geometric_verification = true;
  c.exhaustive_matching = true;
  ASSERT_TRUE(setConfig(d.name(), &c));
  d.publish(test::viewAt(world, 0, kViewWidth), 1000.0);
  ASSERT_TRUE(d.waitForStatuses(1, 20.0));
  const KeyframeStatus s = d.statuses().back();
  EXPECT_EQ(s.lambda_1, 0.65);
  EXPECT_EQ(s.lambda_2, 0.25);
  EXPECT_EQ(s.w_max, 0.4);
  EXPECT_EQ(s.alpha, 0.3);
  EXPECT_EQ(s.fan_bins, 12);
  EXPECT_EQ(s.min_score, 0.25);
  EXPECT_EQ(s.temporal_k, 2);
  EXPECT_EQ(s.min_inliers, 20);
  EXPECT_EQ(s.direct_index_level, 2);
  EXPECT_FALSE(s.word_groups);
  EXPECT_TRUE(s.distribution);
  EXPECT_FALSE(s.temporal_score);
  EXPECT_TRUE(s.geometric_verification);
  EXPECT_TRUE(s.exhaustive_matching);
}

// Invalid combinations are corrected and the client gets the corrected
// values: 0.8 + 0.5 > 1 -> lambda_2 = 1 - 0.8 = 0.2; level 9 deeper than the
// test vocabulary's L = 3 -> 3 (the other values as the previous step left
// them). Then the same through the command line users type (dynparam set).
void expectInvalidValuesCorrected(Detector& d, const cv::Mat& world, BoWGConfig c) {
  c.lambda_1 = 0.8;
  c.lambda_2 = 0.5;
  c.direct_index_level = 9;
  ASSERT_TRUE(setConfig(d.name(), &c));
  EXPECT_NEAR(c.lambda_2, 0.2, 1e-12);
  EXPECT_EQ(c.direct_index_level, 3);
  d.publish(test::viewAt(world, kStep, kViewWidth), 1000.1);
  ASSERT_TRUE(d.waitForStatuses(2, 20.0));
  KeyframeStatus s = d.statuses().back();
  EXPECT_NEAR(s.lambda_2, 0.2, 1e-12);
  EXPECT_EQ(s.direct_index_level, 3);

  const std::string cmd = "rosrun dynamic_reconfigure dynparam set " + d.name() +
                          " \"{'lambda_1': 0.9, 'lambda_2': 0.9}\" > /dev/null 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  d.publish(test::viewAt(world, 2 * kStep, kViewWidth), 1000.2);
  ASSERT_TRUE(d.waitForStatuses(3, 20.0));
  s = d.statuses().back();
  EXPECT_NEAR(s.lambda_1, 0.9, 1e-12);
  EXPECT_NEAR(s.lambda_2, 0.1, 1e-9);
}

// Effects on the scores: with the distribution score off, eq. 5 with
// lambda_1 = 1 gives eta_sim = eta_w; with the temporal score off eta =
// eta_sim; with min_score = 10 no loop is accepted on a revisit.
void expectScoresFollowTheSwitches(Detector& d, const cv::Mat& world) {
  BoWGConfig c = BoWGConfig::__getDefault__();
  c.distribution = false;
  c.lambda_1 = 1.0;
  c.temporal_score = false;
  c.min_score = 10.0;
  ASSERT_TRUE(setConfig(d.name(), &c));
  d.clear();
  const std::vector<int> xs = test::trajectory(kForward, kRevisit, kStep, kOffset);
  const std::vector<int> rest(xs.begin() + 3, xs.end());
  const std::vector<int> light = revisitBrightness();
  ASSERT_TRUE(d.run(world, rest, 1000.3, std::vector<int>(light.begin() + 3, light.end())));
  std::size_t with_candidate = 0;
  for (const KeyframeStatus& k : d.statuses()) {
    EXPECT_NE(k.status, KeyframeStatus::LOOP_DETECTED) << "min_score = 10 accepted a loop";
    if (!k.has_candidate) continue;
    ++with_candidate;
    EXPECT_NEAR(k.best_score_sim, k.best_score_word, 1e-9);
    EXPECT_NEAR(k.best_score, k.best_score_sim, 1e-9);
  }
  EXPECT_GT(with_candidate, 10u);
  EXPECT_TRUE(d.loops().empty());
}

// Back to an accepting threshold: the database survived every change, so
// revisiting the first places again finds loops at once.
void expectDatabaseSurvivedTheChanges(Detector& d, const cv::Mat& world) {
  BoWGConfig c = BoWGConfig::__getDefault__();
  c.distribution = false;
  c.min_score = 0.3;
  c.lambda_1 = 0.5;
  c.temporal_score = true;
  ASSERT_TRUE(setConfig(d.name(), &c));
  d.clear();
  std::vector<int> again;
  for (int j = 0; j < 20; ++j) again.push_back(j * kStep + 2);
  ASSERT_TRUE(d.run(world, again, 1020.0));
  ros::WallDuration(0.3).sleep();
  EXPECT_FALSE(d.loops().empty()) << "database lost after reconfiguration";
}

TEST(LoopDetectorNodelet, LiveParametersTakeEffectAndInvalidValuesAreCorrected) {
  Detector d("/tuning", {});
  ASSERT_TRUE(d.loaded());
  const cv::Mat world = test::makeWorld(kForward * kStep + kViewWidth + kOffset, kViewHeight, 4);
  // Each step stops the scenario at its first fatal failure.
  BoWGConfig c = BoWGConfig::__getDefault__();
  expectEveryParameterInForceNextKeyframe(d, world, &c);
  if (HasFatalFailure()) return;
  expectInvalidValuesCorrected(d, world, c);
  if (HasFatalFailure()) return;
  expectScoresFollowTheSwitches(d, world);
  if (HasFatalFailure()) return;
  expectDatabaseSurvivedTheChanges(d, world);
}

// What a user typing a wrong value or a start-only name is told: dynparam
// knows the start-only parameters (the "start_only" group), the nodelet
// names them and keeps their values; an out-of-range value is refused with
// its range instead of being clamped.
TEST(LoopDetectorNodelet, LiveParametersReportStartOnlyAndOutOfRangeValues) {
  ErrorLog log(rosgraph_msgs::Log::WARN);
  Detector d("/tuning_messages", {});
  ASSERT_TRUE(d.loaded());
  ros::WallDuration(0.5).sleep();  // /rosout connection
  const std::string set = "rosrun dynamic_reconfigure dynparam set " + d.name();
  const std::string quiet = " > /dev/null 2>&1";

  EXPECT_EQ(std::system((set + " orb_levels 3" + quiet).c_str()), 0);
  EXPECT_TRUE(log.waitFor("orb_levels is start-only", 10.0)) << "no message for orb_levels";

  BoWGConfig c = BoWGConfig::__getDefault__();
  c.min_score = 0.6;
  ASSERT_TRUE(setConfig(d.name(), &c));
  EXPECT_EQ(std::system((set + " min_score 99" + quiet).c_str()), 0);
  EXPECT_TRUE(log.waitFor("min_score: 99 is outside [0, 10]", 10.0)) << "no message for 99";
  // The value in force stays 0.6, on the next keyframe and on the server.
  const cv::Mat world = test::makeWorld(kViewWidth + 4 * kStep, kViewHeight, 9);
  d.publish(test::viewAt(world, 0, kViewWidth), 1000.0);
  ASSERT_TRUE(d.waitForStatuses(1, 20.0));
  EXPECT_EQ(d.statuses().back().min_score, 0.6);
  double on_server = 0.0;
  EXPECT_TRUE(ros::param::get(d.name() + "/min_score", on_server));
  EXPECT_EQ(on_server, 0.6);
  // A value in range still applies.
  EXPECT_EQ(std::system((set + " min_score 0.8" + quiet).c_str()), 0);
  d.publish(test::viewAt(world, kStep, kViewWidth), 1000.1);
  ASSERT_TRUE(d.waitForStatuses(2, 20.0));
  EXPECT_EQ(d.statuses().back().min_score, 0.8);
}

TEST(LoopDetectorNodelet, SaveResetLoadRestoresDetectionAndCorruptLoadKeepsTheDatabase) {
  Detector d("/persistence", {});
  ASSERT_TRUE(d.loaded());
  const cv::Mat world = test::makeWorld(kForward * kStep + kViewWidth + kOffset, kViewHeight, 5);
  const std::vector<int> xs = test::trajectory(kForward, kRevisit, kStep, kOffset);
  const std::vector<int> first(xs.begin(), xs.begin() + kForward);
  const std::vector<int> second(xs.begin() + kForward, xs.end());
  ASSERT_TRUE(d.run(world, first, 1000.0));

  const std::string path = std::string(BOWG_TEST_OUTPUT_DIR) + "/bowg_rostest_database.bin";
  std::remove(path.c_str());
  SaveDatabase save;
  save.request.path = path;
  ASSERT_TRUE(ros::service::call(d.name() + "/save_database", save));
  EXPECT_TRUE(save.response.success) << save.response.message;
  EXPECT_EQ(access(path.c_str(), R_OK), 0);

  std_srvs::Trigger reset;
  ASSERT_TRUE(ros::service::call(d.name() + "/reset", reset));
  EXPECT_TRUE(reset.response.success);
  // After the reset the revisit finds nothing: the first pass is forgotten.
  d.clear();
  ASSERT_TRUE(d.run(world, second, 2000.0, std::vector<int>(kRevisit, 12)));
  ros::WallDuration(0.3).sleep();
  EXPECT_TRUE(d.loops().empty());
  EXPECT_EQ(d.statuses().front().database_size, 1u);

  // A corrupt file fails with a message and keeps the running database.
  const std::string corrupt = std::string(BOWG_TEST_OUTPUT_DIR) + "/bowg_rostest_corrupt.bin";
  std::ofstream(corrupt) << "this is not a BoWG database";
  LoadDatabase load;
  load.request.path = corrupt;
  ASSERT_TRUE(ros::service::call(d.name() + "/load_database", load));
  EXPECT_FALSE(load.response.success);
  EXPECT_NE(load.response.message.find(corrupt), std::string::npos) << load.response.message;
  d.clear();
  d.publish(test::viewAt(world, 0, kViewWidth), 2100.0);
  ASSERT_TRUE(d.waitForStatuses(1, 20.0));
  EXPECT_EQ(d.statuses().back().database_size, static_cast<std::uint32_t>(kRevisit + 1));

  // Loading the saved file restores the first pass: the revisit finds loops
  // with the first pass's ids again.
  reset = std_srvs::Trigger();
  ASSERT_TRUE(ros::service::call(d.name() + "/reset", reset));
  load.request.path = path;
  ASSERT_TRUE(ros::service::call(d.name() + "/load_database", load));
  EXPECT_TRUE(load.response.success) << load.response.message;
  d.clear();
  ASSERT_TRUE(d.run(world, second, 3000.0, std::vector<int>(kRevisit, 12)));
  ros::WallDuration(0.3).sleep();
  const std::vector<KeyframeStatus> s = d.statuses();
  ASSERT_FALSE(s.empty());
  EXPECT_EQ(s.front().id, static_cast<std::uint32_t>(kForward));  // ids continue the file's
  const std::vector<LoopClosure> loops = d.loops();
  EXPECT_GE(loops.size(), 5u) << "no detection after load";
  expectRightIds(loops);
}

TEST(LoopDetectorNodelet, DatabaseIsSavedAtShutdownAndLoadedAtStart) {
  const std::string path = std::string(BOWG_TEST_OUTPUT_DIR) + "/bowg_rostest_shutdown.bin";
  std::remove(path.c_str());
  const cv::Mat world = test::makeWorld(kViewWidth + 10 * kStep, kViewHeight, 8);
  {
    Detector d("/shutdown", {{"database_save_path", XmlRpc::XmlRpcValue(path)}});
    ASSERT_TRUE(d.loaded());
    for (int i = 0; i < 3; ++i) d.publish(test::viewAt(world, i * kStep, kViewWidth), 1000.0 + i);
    ASSERT_TRUE(d.waitForStatuses(3, 20.0));
  }  // unloading the nodelet saves
  EXPECT_EQ(access(path.c_str(), R_OK), 0) << "not saved at shutdown";
  Detector d("/startup", {{"database_load_path", XmlRpc::XmlRpcValue(path)}});
  ASSERT_TRUE(d.loaded());
  d.publish(test::viewAt(world, 5 * kStep, kViewWidth), 2000.0);
  ASSERT_TRUE(d.waitForStatuses(1, 20.0));
  EXPECT_EQ(d.statuses()[0].id, 3u);
  EXPECT_EQ(d.statuses()[0].database_size, 4u);
}

// A robot's second survey against its first survey's saved database: its
// keyframes are in its own mission, and its loops into the first survey say
// which mission they are from.
TEST(LoopDetectorNodelet, MissionsNameTheKeyframesAndLoopsIntoALoadedMissionSayWhichOne) {
  const std::string path = std::string(BOWG_TEST_OUTPUT_DIR) + "/bowg_rostest_missions.bin";
  std::remove(path.c_str());
  const cv::Mat world = test::makeWorld(kForward * kStep + kViewWidth + kOffset, kViewHeight, 5);
  const std::vector<int> xs = test::trajectory(kForward, kRevisit, kStep, kOffset);
  {
    Detector first("/survey_2025", {{"database_save_path", XmlRpc::XmlRpcValue(path)},
                                    {"mission_name", XmlRpc::XmlRpcValue("2025-05 Kanal 7")},
                                    {"mission_id", XmlRpc::XmlRpcValue(4)}});
    ASSERT_TRUE(first.loaded());
    ASSERT_TRUE(first.run(world, std::vector<int>(xs.begin(), xs.begin() + kForward), 1000.0));
  }  // saved at shutdown
  Detector second("/survey_2026", {{"database_load_path", XmlRpc::XmlRpcValue(path)},
                                   {"mission_name", XmlRpc::XmlRpcValue("2026-05 Kanal 7")},
                                   {"mission_id", XmlRpc::XmlRpcValue(7)}});
  ASSERT_TRUE(second.loaded());
  ASSERT_TRUE(second.run(world, std::vector<int>(xs.begin() + kForward, xs.end()), 2000.0,
                         std::vector<int>(kRevisit, 12)));
  ros::WallDuration(0.3).sleep();
  const std::vector<LoopClosure> loops = second.loops();
  EXPECT_GE(loops.size(), 5u) << "the second survey finds the first one's places";
  for (const LoopClosure& l : loops) {
    EXPECT_EQ(l.query_mission, 7u);
    ASSERT_LT(l.match_id, static_cast<std::uint32_t>(kForward));
    EXPECT_EQ(l.match_mission, 4u);
    EXPECT_EQ(l.match_mission_name, "2025-05 Kanal 7");
  }
  expectRightIds(loops);
}

// Two earlier surveys, each saved into its own file, as the reference maps of
// a third: its revisit finds the places of both, each loop naming its
// mission; the ids are the merged files' (first survey first).
TEST(LoopDetectorNodelet, ReferenceMapsOfTwoSurveysAreSearchedTogether) {
  const std::string dir = std::string(BOWG_TEST_OUTPUT_DIR);
  const std::string first = dir + "/bowg_rostest_reference_1.bin";
  const std::string second = dir + "/bowg_rostest_reference_2.bin";
  const cv::Mat world = test::makeWorld(kForward * kStep + kViewWidth + kOffset, kViewHeight, 5);
  const std::vector<int> xs = test::trajectory(kForward, kRevisit, kStep, kOffset);
  const int split = 15;
  const std::vector<std::pair<std::string, std::vector<int>>> surveys = {
      {first, std::vector<int>(xs.begin(), xs.begin() + split)},
      {second, std::vector<int>(xs.begin() + split, xs.begin() + kForward)}};
  for (std::size_t k = 0; k < surveys.size(); ++k) {
    std::remove(surveys[k].first.c_str());
    Detector d("/reference_" + std::to_string(k),
               {{"database_save_path", XmlRpc::XmlRpcValue(surveys[k].first)},
                {"mission_name", XmlRpc::XmlRpcValue("survey " + std::to_string(k + 1))},
                {"mission_id", XmlRpc::XmlRpcValue(static_cast<int>(k + 1))}});
    ASSERT_TRUE(d.loaded());
    ASSERT_TRUE(d.run(world, surveys[k].second, 1000.0 + 100.0 * k));
  }
  XmlRpc::XmlRpcValue maps;
  maps[0] = second;  // any order: the merge orders them by time
  maps[1] = first;
  Detector third("/reference_3",
                 {{"reference_maps", maps}, {"mission_name", XmlRpc::XmlRpcValue("survey 3")}});
  ASSERT_TRUE(third.loaded());
  ASSERT_TRUE(third.run(world, std::vector<int>(xs.begin() + kForward, xs.end()), 2000.0,
                        std::vector<int>(kRevisit, 12)));
  ros::WallDuration(0.3).sleep();
  const std::vector<LoopClosure> loops = third.loops();
  std::set<std::uint32_t> missions;
  for (const LoopClosure& l : loops) {
    EXPECT_EQ(l.query_mission, 3u);  // the next free id
    const std::uint32_t expected = l.match_id < static_cast<std::uint32_t>(split) ? 1u : 2u;
    EXPECT_EQ(l.match_mission, expected) << "match " << l.match_id;
    EXPECT_EQ(l.match_mission_name, "survey " + std::to_string(expected));
    missions.insert(l.match_mission);
  }
  EXPECT_EQ(missions.size(), 2u) << loops.size() << " loops";
  expectRightIds(loops);

  // The two surveys merged by the nodelet's service: one file that loads
  // with both; a file merged with itself is refused and nothing written.
  const std::string merged = dir + "/bowg_rostest_merged.bin";
  std::remove(merged.c_str());
  MergeDatabases merge;
  merge.request.paths = {first, first};
  merge.request.output = merged;
  ASSERT_TRUE(ros::service::call(third.name() + "/merge_databases", merge));
  EXPECT_FALSE(merge.response.success);
  EXPECT_NE(merge.response.message.find("merged with itself"), std::string::npos)
      << merge.response.message;
  EXPECT_NE(access(merged.c_str(), F_OK), 0) << "written on error";
  merge.request.paths = {second, first};
  ASSERT_TRUE(ros::service::call(third.name() + "/merge_databases", merge));
  EXPECT_TRUE(merge.response.success) << merge.response.message;
  EXPECT_NE(merge.response.message.find(std::to_string(kForward) + " keyframes, 2 missions"),
            std::string::npos)
      << merge.response.message;
  LoadDatabase load;
  load.request.path = merged;
  ASSERT_TRUE(ros::service::call(third.name() + "/load_database", load));
  EXPECT_TRUE(load.response.success) << load.response.message;
  EXPECT_NE(load.response.message.find("loaded " + std::to_string(kForward) + " keyframes"),
            std::string::npos)
      << load.response.message;
}

// A survey already under way loads an earlier survey as its reference map
// (~load_reference_maps): its keyframes so far are kept, after the map's, and
// its next frames find loops into the map, each naming the earlier survey. A
// file that cannot be read is refused by name and the running database kept.
TEST(LoopDetectorNodelet, ReferenceMapsLoadedLiveKeepTheRunningSurvey) {
  const std::string map = std::string(BOWG_TEST_OUTPUT_DIR) + "/bowg_rostest_live_map.bin";
  std::remove(map.c_str());
  const cv::Mat world = test::makeWorld(kForward * kStep + kViewWidth + kOffset, kViewHeight, 5);
  const std::vector<int> xs = test::trajectory(kForward, kRevisit, kStep, kOffset);
  {
    Detector first("/live_map_survey", {{"database_save_path", XmlRpc::XmlRpcValue(map)},
                                        {"mission_name", XmlRpc::XmlRpcValue("survey A")},
                                        {"mission_id", XmlRpc::XmlRpcValue(1)}});
    ASSERT_TRUE(first.loaded());
    ASSERT_TRUE(first.run(world, std::vector<int>(xs.begin(), xs.begin() + kForward), 1000.0));
  }  // saved at shutdown
  Detector d("/live_map", {{"mission_name", XmlRpc::XmlRpcValue("survey B")},
                           {"mission_id", XmlRpc::XmlRpcValue(4)}});
  ASSERT_TRUE(d.loaded());
  const auto revisit = xs.begin() + kForward;
  ASSERT_TRUE(d.run(world, std::vector<int>(revisit, revisit + 3), 2000.0));

  LoadReferenceMaps load;
  load.request.paths = {map + ".missing"};
  ASSERT_TRUE(ros::service::call(d.name() + "/load_reference_maps", load));
  EXPECT_FALSE(load.response.success);
  EXPECT_NE(load.response.message.find(map + ".missing"), std::string::npos)
      << load.response.message;
  load.request.paths = {map};
  ASSERT_TRUE(ros::service::call(d.name() + "/load_reference_maps", load));
  EXPECT_TRUE(load.response.success) << load.response.message;
  EXPECT_NE(load.response.message.find(std::to_string(kForward + 3) + " keyframes"),
            std::string::npos)
      << load.response.message;
  d.clear();
  ASSERT_TRUE(d.run(world, std::vector<int>(revisit + 3, xs.end()), 2100.0,
                    std::vector<int>(kRevisit - 3, 12)));
  ros::WallDuration(0.3).sleep();
  const std::vector<KeyframeStatus> s = d.statuses();
  ASSERT_FALSE(s.empty());
  EXPECT_EQ(s.front().database_size, static_cast<std::uint32_t>(kForward + 4));
  EXPECT_EQ(s.front().query_mission, 4u);
  const std::vector<LoopClosure> loops = d.loops();
  EXPECT_GE(loops.size(), 5u) << "the running survey finds the map's places";
  for (const LoopClosure& l : loops) {
    EXPECT_EQ(l.query_mission, 4u);
    if (l.match_id < static_cast<std::uint32_t>(kForward)) {
      EXPECT_EQ(l.match_mission, 1u);
      EXPECT_EQ(l.match_mission_name, "survey A");
    }
  }
  expectRightIds(loops);
}

}  // namespace
}  // namespace bowg_ros

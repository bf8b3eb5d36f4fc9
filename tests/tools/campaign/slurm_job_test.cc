// The Slurm job script's time check: Slurm's time formats, and the warning when a task's runs,
// each up to limits.time_s and cpus_per_task at a time, may outlast slurm.time.
#include "tools/campaign/slurm_job.h"

#include <gtest/gtest.h>

#include "tests/tools/campaign/campaign_test_util.h"
#include "tools/campaign/campaign_file.h"

namespace criticality::campaign {
namespace {

using testing::TempDir;
using testing::WriteFile;

TEST(SlurmJob, SlurmTimesInEveryFormat) {
  EXPECT_EQ(SlurmTimeSeconds("10"), 600.0);  // minutes
  EXPECT_EQ(SlurmTimeSeconds("10:30"), 630.0);
  EXPECT_EQ(SlurmTimeSeconds("01:02:03"), 3723.0);
  EXPECT_EQ(SlurmTimeSeconds("2-3"), 2 * 86400.0 + 3 * 3600.0);
  EXPECT_EQ(SlurmTimeSeconds("1-00:10"), 86400.0 + 600.0);
  EXPECT_EQ(SlurmTimeSeconds("1-00:00:30"), 86430.0);
  EXPECT_EQ(SlurmTimeSeconds(""), -1.0);
  EXPECT_EQ(SlurmTimeSeconds("unlimited"), -1.0);
  EXPECT_EQ(SlurmTimeSeconds("1:2:3:4"), -1.0);
  EXPECT_EQ(SlurmTimeSeconds("99999999999999999999"), -1.0);  // no overflow
}

// 10 runs in tasks of 5 (max_array_size 2), each run up to 120 s: 600 s per task on one CPU.
SlurmJob JobOf(const TempDir& d, const std::string& slurm) {
  WriteFile(d / "a/scenario.cfg", "sumo-config = x.sumocfg\n");
  WriteFile(d / "c.yaml",
            "output: out\nscenarios: [a/scenario.cfg]\ngrid:\n  sumo:\n    seed: {range: [1, 10]}\n"
            "limits:\n  time_s: 120\nslurm:\n  max_array_size: 2\n" +
                slurm);
  const Plan plan(LoadCampaignFile(d / "c.yaml"));
  const CampaignFolder folder = CampaignFolder::Prepare(d / "out", plan, false);
  return MakeSlurmJob(plan, folder, "/bin/criticality-campaign", "/bin/sumo-criticality", 120.0);
}

TEST(SlurmJob, ATaskWhoseRunsMayOutlastItsTimeIsSaidSo) {
  TempDir a, b, c, e;
  const SlurmJob tight = JobOf(a, "  time: \"00:10:00\"\n");
  EXPECT_EQ(tight.runs_per_task, 5u);
  EXPECT_NE(tight.time_warning.find("up to 600 s, not less than slurm.time 00:10:00"),
            std::string::npos)
      << tight.time_warning;
  EXPECT_TRUE(JobOf(b, "  time: \"00:10:01\"\n").time_warning.empty());
  // Two CPUs: three waves of runs, 360 s.
  EXPECT_TRUE(JobOf(c, "  time: \"7\"\n  cpus_per_task: 2\n").time_warning.empty());
  EXPECT_TRUE(JobOf(e, "").time_warning.empty());  // no slurm.time: the cluster's default
}

}  // namespace
}  // namespace criticality::campaign

// igabde under mpirun: input errors are refused by every rank with one
// message and exit status 2; an error during the run ends all ranks with
// the failing rank's message and leaves no summary that says ok. Three
// ranks on the machine's two cores (--oversubscribe), as CI runs them.

#include <gtest/gtest.h>

#include "cli_helpers.h"
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

namespace
{
  // mpirun with three ranks (as root too: CI runs as root). This test
  // program is an MPI process itself (deal.II initialises MPI): its Open
  // MPI and PMIx variables are not handed to the new job.
  std::string
  mpirun(const std::string &arguments)
  {
    return "unset $(env | sed -n 's/^\\(OMPI_[^=]*\\|PMIX_[^=]*\\|"
           "OPAL_[^=]*\\)=.*/\\1/p'); "
           "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 "
           "timeout 120 mpirun --oversubscribe -np 3 " +
           cli::executable() + " " + arguments;
  }

  unsigned int
  count(const std::string &text, const std::string &what)
  {
    unsigned int n = 0;
    for (auto at = text.find(what); at != std::string::npos;
         at      = text.find(what, at + 1))
      ++n;
    return n;
  }
} // namespace



TEST(CliMpi, BadInputIsRefusedOnceWithStatusTwo)
{
  cli::ScratchFolder folder("mpi", "bad-input");
  {
    std::ofstream scene(cli::join(folder.path, "bad.prm"));
    scene << "set Dimension = 2\n"
             "subsection Contact\n"
             "  set Tolerance = 0\n"
             "end\n";
  }
  const auto r = cli::run_in(folder.path, mpirun("bad.prm"));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_EQ(count(r.output, "igabde: error:"), 1u) << r.output;
  EXPECT_NE(r.output.find("Contact/Tolerance"), std::string::npos) << r.output;
}



TEST(CliMpi, ARunThatFailsEndsEveryRankAndSaysFailed)
{
  // V4 with one B-Newton iteration and no step cuts cannot converge: the
  // run fails in its first load step, on every rank.
  cli::ScratchFolder folder("mpi", "late-failure");
  const std::string  out = cli::join(folder.path, "out");
  const auto         r =
    cli::run_in(folder.path,
                mpirun(cli::join(std::string(IGABDE_SOURCE_DIR),
                                 "prm/v4-sliding-block.prm") +
                       " --quiet --set 'Output/Directory=" + out +
                       "' --set 'Output/Write vtu=false' --set 'Contact/Max "
                       "iterations=1' --set 'Contact/Max step cuts=0'"));
  EXPECT_NE(r.status, 0) << r.output;
  EXPECT_NE(r.status, 124) << "mpirun hung:\n" << r.output;
  EXPECT_NE(r.output.find("igabde: error: [rank "), std::string::npos)
    << r.output;
  EXPECT_NE(r.output.find("did not converge"), std::string::npos) << r.output;
  std::ifstream in(cli::join(out, "summary.json"));
  ASSERT_TRUE(in);
  const auto summary = nlohmann::json::parse(in);
  EXPECT_NE(summary["status"], "ok");
}

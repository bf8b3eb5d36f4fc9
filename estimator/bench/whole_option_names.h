#pragma once
// The benches' command lines: whole option names only. Boost's default style also takes an
// unambiguous prefix, so a misspelt option ran as another one, unannounced (--rep 2 as
// --repeat 2); the driver and the campaign tool parse the same way.
#include <boost/program_options.hpp>

namespace criticality::bench {

inline void StoreWholeNames(int argc, char** argv,
                            const boost::program_options::options_description& desc,
                            boost::program_options::variables_map* vm) {
  namespace po = boost::program_options;
  po::store(po::command_line_parser(argc, argv)
                .options(desc)
                .style(po::command_line_style::default_style &
                       ~po::command_line_style::allow_guessing)
                .run(),
            *vm);
}

}  // namespace criticality::bench

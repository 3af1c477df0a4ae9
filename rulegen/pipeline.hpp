// rulegen's whole run (load and validate the catalog, derive, optionally emit) as a library call,
// so that tests run it in-process (the catalog fuzz test) with the same exit statuses as the tool.
#pragma once

#include <ostream>
#include <string>

namespace bl::rulegen {

struct Options {
  std::string catalog;                          // catalog JSON file
  std::string catalog_text;                     // or its text (used when not empty)
  std::string out;                              // emit: output directory ("" = derive only)
  std::string label = "symbolic/catalog.json";  // catalog path recorded in the manifest
  bool quiet = false;                           // print only the summary
  int max_moment = 16;
};

// Exit status: 0 done, 2 the catalog is wrong (message on err names file, entry and field),
// 3 internal error (a bug: nothing in a catalog should cause it).
int run(const Options& opt, std::ostream& out, std::ostream& err);

}  // namespace bl::rulegen

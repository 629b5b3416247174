// The page's files, built from tools/ide/web by the Makefile and compiled
// into the program (so that one file is all a lab PC needs).

#pragma once

#include <vector>

#include "web_server.hpp"

namespace aseba::ide
{

// Every file of the built page, with its path and content type.
std::vector<StaticFile> web_assets();

} // namespace aseba::ide

// The command lines of every program of the project (asebac, aseba,
// epuck-emu, epuck-image, aseba-ide, aseba-mqtt) over CLI11, in one style:
// help that starts with hand-written usage lines, then what the program or
// command does, then the options CLI11 knows (so the list cannot drift from
// the parser), one set of exit statuses, and output that is checked.

#pragma once

#include <CLI/CLI.hpp>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <string_view>

namespace aseba::command_line
{

// Exit statuses of every program.
constexpr int EXIT_OK = 0;
constexpr int EXIT_FAILED = 1; // the work failed: a compile error, a node, the network
constexpr int EXIT_USAGE = 2;  // a bad command line, or an input file that cannot be used

// The line every --help ends with.
inline constexpr const char *EXIT_STATUS_TEXT =
  "Exit status: 0 on success, 1 when the work fails (a compile error, a node, the\n"
  "network, a port already in use), 2 on bad usage (a malformed option or target)\n"
  "or an input file that cannot be read or used.";

// Help as: usage lines, a blank line, the description, the options.
class HelpFormatter : public CLI::Formatter
{
  public:
    HelpFormatter()
    {
        label("Positionals", "Arguments");
    }

    // The usage lines of `app` ("usage: PROGRAM ..."), shown first, and what
    // it does in some sentences (else its one-line description).
    void set_usage(const CLI::App *app, std::string usage, std::string details = "")
    {
        usages_[app] = std::move(usage);
        if (!details.empty())
            details_[app] = std::move(details);
    }

    std::string make_usage(const CLI::App *app, std::string name) const override
    {
        auto found = usages_.find(app);
        if (found == usages_.end())
            return CLI::Formatter::make_usage(app, name);
        return found->second + "\n";
    }

    std::string make_help(const CLI::App *app,
                          std::string name,
                          CLI::AppFormatMode mode) const override
    {
        if (mode == CLI::AppFormatMode::Sub)
            return make_expanded(app);
        std::string help = make_usage(app, name);
        auto details = details_.find(app);
        std::string about = details != details_.end() ? details->second : app->get_description();
        if (!about.empty())
            help += "\n" + about + "\n";
        // CLI11's lists start with a blank line.
        help += make_positionals(app) + make_groups(app, mode) + make_subcommands(app, mode);
        if (!app->get_footer().empty())
            help += "\n" + app->get_footer() + "\n";
        return help;
    }

  private:
    std::map<const CLI::App *, std::string> usages_;
    std::map<const CLI::App *, std::string> details_;
};

// Gives `app` (and the subcommands created after) the common formatter and
// the -h/--help flag; returns the formatter for set_usage.
inline std::shared_ptr<HelpFormatter> use_common_style(CLI::App &app)
{
    auto formatter = std::make_shared<HelpFormatter>();
    app.formatter(formatter);
    app.set_help_flag("-h,--help", "show this help and exit");
    app.option_defaults()->always_capture_default(false);
    return formatter;
}

// "PROGRAM: MESSAGE" and the hint to --help, on standard error.
inline void print_usage_error(const std::string &program, const std::string &message)
{
    std::cerr << program << ": " << message << "\n(" << program << " --help for usage)\n";
}

// The exit status of a program that ends with `status`, once what it wrote
// to standard output has reached it: a full disk or a closed pipe is the
// work failing (EXIT_FAILED unless it failed already), said on standard
// error as "PROGRAM: cannot write to standard output: REASON".
inline int finish_standard_output(const std::string &program, int status)
{
    // std::cout writes through stdout (synchronised with stdio).
    std::cout.flush();
    errno = 0;
    bool flushed = std::fflush(stdout) == 0;
    int reason = errno;
    if (flushed && !std::ferror(stdout) && std::cout.good())
        return status;
    std::cerr << program << ": cannot write to standard output"
              << (reason != 0 ? std::string(": ") + std::strerror(reason) : "") << "\n";
    return status == EXIT_OK ? EXIT_FAILED : status;
}

// Writes `content` to the file `path`, replacing it; "" when all of it was
// written (flushed and closed), else why not.
inline std::string write_whole_file(const std::string &path, std::string_view content)
{
    std::ofstream file(path, std::ios::binary | std::ios::trunc);
    if (!file)
        return path + ": cannot be written: " + std::strerror(errno);
    errno = 0;
    file.write(content.data(), std::streamsize(content.size()));
    file.close();
    if (!file)
        return path + ": cannot be written" +
               (errno != 0 ? std::string(": ") + std::strerror(errno) : "");
    return "";
}

// Parses `argv`; prints the help and exits 0 when asked (1 when it cannot be
// written), prints the error and exits EXIT_USAGE on bad usage. Returns only
// when the command line is good.
inline void parse_or_exit(CLI::App &app, int argc, char **argv)
{
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp &) {
        std::cout << app.help();
        std::exit(finish_standard_output(app.get_name(), EXIT_OK));
    } catch (const CLI::CallForAllHelp &) {
        std::cout << app.help("", CLI::AppFormatMode::All);
        std::exit(finish_standard_output(app.get_name(), EXIT_OK));
    } catch (const CLI::ParseError &error) {
        print_usage_error(app.get_name(), error.what());
        std::exit(EXIT_USAGE);
    }
}

} // namespace aseba::command_line

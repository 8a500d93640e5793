#include "experiments/cli/argument_checks.hpp"

#include <cerrno>
#include <cstdlib>

#include "experiments/errors/exit_status.hpp"

namespace lgi::experiments {
namespace {

bool has_empty_element(const std::string& list, char delimiter) {
  if (list.empty() || list.front() == delimiter || list.back() == delimiter) return true;
  return list.find(std::string(2, delimiter)) != std::string::npos;
}

/// The option `token` ("--name" or "--name=value") names in `sub`, or nullptr.
const CLI::Option* option_of(const CLI::App& sub, const std::string& token, std::string& value, bool& inline_value) {
  if (token.size() < 3 || token.compare(0, 2, "--") != 0) return nullptr;
  const auto eq = token.find('=');
  inline_value = eq != std::string::npos;
  if (inline_value) value = token.substr(eq + 1);
  return sub.get_option_no_throw(token.substr(0, inline_value ? eq : std::string::npos));
}

/// CLI11 2.1 converts integers with strtoll / strtoull and ignores ERANGE: a value past the
/// type's range saturates, and strtoull takes "-1" as 2^64 - 1. Refused here instead.
void check_integer_range(const CLI::Option& opt, const std::string& value) {
  const std::string type = opt.get_type_name();
  const bool is_unsigned = type.rfind("UINT", 0) == 0;
  if (!is_unsigned && type.rfind("INT", 0) != 0) return;
  if (is_unsigned && value.find('-') != std::string::npos)
    throw UsageError(opt.get_name() + ": '" + value + "' is negative; expected a count >= 0");
  errno = 0;
  char* end = nullptr;
  if (is_unsigned) (void)std::strtoull(value.c_str(), &end, 0);
  else (void)std::strtoll(value.c_str(), &end, 0);
  if (errno == ERANGE) throw UsageError(opt.get_name() + ": '" + value + "' is out of range of a 64-bit integer");
}

}  // namespace

void check_argument_values(const CLI::App& sub, int argc, const char* const* argv) {
  for (int i = 1; i < argc; ++i) {
    std::string value;
    bool inline_value = false;
    const std::string token = argv[i];
    const CLI::Option* opt = option_of(sub, token, value, inline_value);
    if (opt == nullptr || opt->get_type_size_max() == 0) continue;  // not an option of sub, or a flag
    if (!inline_value) {
      if (i + 1 >= argc) continue;  // CLI11 has refused a missing value already
      value = argv[++i];
    }
    const std::string name = opt->get_name();
    if (value.empty()) throw UsageError(name + ": an empty value");
    if (opt->get_delimiter() != '\0' && has_empty_element(value, opt->get_delimiter()))
      throw UsageError(name + ": an empty element in '" + value + "'");
    if (opt->get_delimiter() == '\0') check_integer_range(*opt, value);
  }
}

std::string unknown_leading_argument(const CLI::App& app, int argc, const char* const* argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string token = argv[i];
    if (token.empty()) return "lgi: an empty argument where a subcommand is expected (see lgi --help)";
    if (token[0] == '-') {
      const std::string name = token.substr(0, token.find('='));
      if (app.get_option_no_throw(name) == nullptr)
        return "lgi: unknown option '" + name + "' before the subcommand (see lgi --help)";
      continue;
    }
    try {
      (void)app.get_subcommand(token);
    } catch (const CLI::Error&) {
      return "lgi: unknown subcommand '" + token + "' (lgi --help lists them)";
    }
    return "";
  }
  return "";
}

}  // namespace lgi::experiments

// Command-line parsing and help text.
#include "cli/args.h"

#include <charconv>
#include <filesystem>
#include <iostream>
#include <new>
#include <cmath>

#include "core/error.h"

namespace qf::cli {

std::string ParsedArgs::get(const std::string& name, const std::string& fallback) const {
  const auto it = values_.find(name);
  return it == values_.end() ? fallback : it->second;
}

long long ParsedArgs::get_int(const std::string& name, long long fallback, long long min, long long max) const {
  if (!has(name)) return fallback;
  const std::string v = get(name);
  long long out = 0;
  const auto r = std::from_chars(v.data(), v.data() + v.size(), out);
  if (r.ec != std::errc() || r.ptr != v.data() + v.size() || out < min || out > max)
    throw UsageError("--" + name + " expects an integer in " + std::to_string(min) + ".." + std::to_string(max) +
                     ", got '" + v + "'");
  return out;
}

double ParsedArgs::get_double(const std::string& name, double fallback, double min, double max) const {
  if (!has(name)) return fallback;
  const std::string v = get(name);
  double out = 0;
  const auto r = std::from_chars(v.data(), v.data() + v.size(), out);
  if (r.ec != std::errc() || r.ptr != v.data() + v.size() || !std::isfinite(out) || out < min || out > max)
    throw UsageError("--" + name + " expects a number in [" + std::to_string(min) + ", " + std::to_string(max) +
                     "], got '" + v + "'");
  return out;
}

static const OptionSpec* find_long(const CommandSpec& spec, const std::string& name) {
  for (const OptionSpec& o : spec.options)
    if (o.name == name) return &o;
  return nullptr;
}

static const OptionSpec* find_short(const CommandSpec& spec, char c) {
  for (const OptionSpec& o : spec.options)
    if (o.short_name == c) return &o;
  return nullptr;
}

ParsedArgs parse_args(const CommandSpec& spec, const std::vector<std::string>& args) {
  ParsedArgs out;
  bool options_done = false;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (options_done || a.size() < 2 || a[0] != '-') {
      out.positional.push_back(a);
      continue;
    }
    if (a == "--") {
      options_done = true;
      continue;
    }
    const OptionSpec* o = nullptr;
    std::string inline_value;
    bool has_inline = false;
    if (a[1] == '-') {
      std::string name = a.substr(2);
      const std::size_t eq = name.find('=');
      if (eq != std::string::npos) {
        inline_value = name.substr(eq + 1);
        has_inline = true;
        name.resize(eq);
      }
      o = find_long(spec, name);
    } else if (a.size() == 2) {
      o = find_short(spec, a[1]);
    }
    if (!o) throw UsageError("unknown option '" + a + "' for '" + spec.program + " " + spec.name + "' (see " + spec.program + " " + spec.name + " --help)");
    if (o->metavar.empty()) {
      if (has_inline) throw UsageError("option --" + o->name + " takes no value");
      out.values_[o->name] = "";
      continue;
    }
    if (has_inline) {
      out.values_[o->name] = inline_value;
    } else {
      if (i + 1 >= args.size()) throw UsageError("option --" + o->name + " needs a value (" + o->metavar + ")");
      out.values_[o->name] = args[++i];
    }
  }
  if (out.positional.size() < spec.min_positional || out.positional.size() > spec.max_positional)
    throw UsageError("usage: " + spec.program + " " + spec.name + " " + spec.usage + " (see " + spec.program + " " + spec.name + " --help)");
  return out;
}

std::string help_text(const CommandSpec& spec) {
  std::string s = "usage: " + spec.program + (spec.name.empty() ? "" : " " + spec.name) + " " + spec.usage + "\n\n" + spec.summary + "\n";
  if (!spec.details.empty()) s += "\n" + spec.details + "\n";
  if (!spec.options.empty()) s += "\noptions:\n";
  for (const OptionSpec& o : spec.options) {
    std::string left = "  ";
    left += o.short_name ? std::string("-") + o.short_name + ", " : "    ";
    left += "--" + o.name;
    if (!o.metavar.empty()) left += " " + o.metavar;
    if (left.size() < 30) left.resize(30, ' ');
    else left += "\n" + std::string(30, ' ');
    std::string help = o.help;  // continuation lines line up under the first
    for (std::size_t at = help.find('\n'); at != std::string::npos; at = help.find('\n', at + 31)) help.insert(at + 1, 30, ' ');
    s += left + help;
    if (!o.default_text.empty()) s += " (default: " + o.default_text + ")";
    s += "\n";
  }
  s += "  -h, --help                  show this help\n";
  return s;
}

bool asks_for_help(const std::vector<std::string>& args) {
  for (const std::string& a : args) {
    if (a == "--") break;
    if (a == "--help" || a == "-h") return true;
  }
  return false;
}

int run_with_exit_codes(const std::string& program, const std::function<int()>& body, int bad_input) {
  try {
    return body();
  } catch (const InputError& e) {
    std::cerr << program << ": error: " << e.what() << "\n";
    return bad_input;
  } catch (const UsageError& e) {
    std::cerr << program << ": " << e.what() << "\n";
    return static_cast<int>(ExitCode::kUsage);
  } catch (const std::filesystem::filesystem_error& e) {
    // Output paths that cannot be written (missing folder, no permission) are a usage problem.
    std::cerr << program << ": cannot write output: " << e.what() << "\n";
    return static_cast<int>(ExitCode::kUsage);
  } catch (const std::bad_alloc&) {
    std::cerr << program << ": internal error: out of memory\n";
    return static_cast<int>(ExitCode::kInternal);
  } catch (const std::exception& e) {
    std::cerr << program << ": internal error: " << e.what() << "\n";
    return static_cast<int>(ExitCode::kInternal);
  }
}

}  // namespace qf::cli

// Command-line parsing, typed option readers, help text and the exit-code frame.
#include "cli/args.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>

#include "core/error.h"

namespace qf::cli {

std::string ParsedArgs::get(const std::string& name, const std::string& fallback) const {
  const auto it = values_.find(name);
  return it == values_.end() ? fallback : it->second;
}

namespace {

// A whole string as a number of type T (from_chars: no sign prefix '+', no trailing text).
template <class T>
bool parse_number(const std::string& v, T& out) {
  const auto r = std::from_chars(v.data(), v.data() + v.size(), out);
  return r.ec == std::errc() && r.ptr == v.data() + v.size();
}

std::string integers_in(long long min, long long max) {
  constexpr long long kMax = std::numeric_limits<long long>::max();
  if (max == kMax && min == 1) return "positive integers";
  if (max == kMax && min == std::numeric_limits<long long>::min()) return "integers";
  return "integers in " + std::to_string(min) + ".." + std::to_string(max);
}

std::string numbers_in(double min, double max) {
  if (max == std::numeric_limits<double>::max() && min == std::numeric_limits<double>::min()) return "positive numbers";
  return "numbers in [" + std::to_string(min) + ", " + std::to_string(max) + "]";
}

// "a,b,,c" -> {"a", "b", "c"}: the comma-separated list options.
std::vector<std::string> split_list(const std::string& s) {
  std::vector<std::string> out;
  std::size_t a = 0;
  while (a <= s.size()) {
    std::size_t b = s.find(',', a);
    if (b == std::string::npos) b = s.size();
    if (b > a) out.push_back(s.substr(a, b - a));
    a = b + 1;
  }
  return out;
}

}  // namespace

long long parse_int_option(const std::string& name, const std::string& v, long long min, long long max) {
  long long out = 0;
  if (!parse_number(v, out) || out < min || out > max)
    throw UsageError("--" + name + " expects an integer in " + std::to_string(min) + ".." + std::to_string(max) +
                     ", got '" + v + "'");
  return out;
}

double parse_double_option(const std::string& name, const std::string& v, double min, double max) {
  double out = 0;
  // Bounds as written (%g: 0 and 1e+06, not 0.000000 and 1000000.000000).
  const auto shown = [](double x) {
    char b[32];
    std::snprintf(b, sizeof b, "%g", x);
    return std::string(b);
  };
  if (!parse_number(v, out) || !std::isfinite(out) || out < min || out > max)
    throw UsageError("--" + name + " expects a number in [" + shown(min) + ", " + shown(max) + "], got '" + v + "'");
  return out;
}

std::vector<long long> parse_int_list_option(const std::string& name, const std::string& text, long long min, long long max) {
  std::vector<long long> out;
  for (const std::string& t : split_list(text)) {
    long long v = 0;
    if (!parse_number(t, v) || v < min || v > max)
      throw UsageError("--" + name + " expects " + integers_in(min, max) + " separated by commas, got '" + t + "'");
    out.push_back(v);
  }
  return out;
}

std::vector<double> parse_double_list_option(const std::string& name, const std::string& text, double min, double max) {
  std::vector<double> out;
  for (const std::string& t : split_list(text)) {
    double v = 0;
    if (!parse_number(t, v) || !std::isfinite(v) || v < min || v > max)
      throw UsageError("--" + name + " expects " + numbers_in(min, max) + " separated by commas, got '" + t + "'");
    out.push_back(v);
  }
  return out;
}

std::string OptionValues::get_choice(const std::string& name, const std::vector<std::string>& choices, const std::string& fallback) const {
  const std::string v = get(name, fallback);
  for (const std::string& c : choices)
    if (c == v) return v;
  std::string all;
  for (std::size_t i = 0; i < choices.size(); ++i) all += (i == 0 ? "" : i + 1 == choices.size() ? " or " : ", ") + choices[i];
  throw UsageError("--" + name + " expects " + all + ", got '" + v + "'");
}

long long ParsedArgs::get_int(const std::string& name, long long fallback, long long min, long long max) const {
  return has(name) ? parse_int_option(name, get(name), min, max) : fallback;
}

double ParsedArgs::get_double(const std::string& name, double fallback, double min, double max) const {
  return has(name) ? parse_double_option(name, get(name), min, max) : fallback;
}

std::vector<long long> ParsedArgs::get_int_list(const std::string& name, long long min, long long max) const {
  return parse_int_list_option(name, get(name), min, max);
}

std::vector<double> ParsedArgs::get_double_list(const std::string& name, double min, double max) const {
  return parse_double_list_option(name, get(name), min, max);
}

// "qf-bake info" / "qf-diff": how the usage and error lines name the command.
static std::string command_line(const CommandSpec& spec) { return spec.program + (spec.name.empty() ? "" : " " + spec.name); }

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

std::string ParsedArgs::require(const std::string& name) const {
  if (has(name)) return get(name);
  std::string shown = "--" + name;
  for (const OptionSpec& o : spec_.options)
    if (o.name == name) shown = (o.short_name ? std::string("-") + o.short_name : "--" + name) + (o.metavar.empty() ? "" : " " + o.metavar);
  throw UsageError(spec_.name + " needs " + shown + " (see " + command_line(spec_) + " --help)");
}

OptionSpec output_option(const std::string& metavar, const std::string& help) { return {"output", 'o', metavar, "", help}; }
OptionSpec quiet_option() { return {"quiet", 'q', "", "", "print nothing on success"}; }

ParsedArgs parse_args(const CommandSpec& spec, const std::vector<std::string>& args) {
  ParsedArgs out;
  out.spec_ = spec;
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
    if (!o) throw UsageError("unknown option '" + a + "' for '" + command_line(spec) + "' (see " + command_line(spec) + " --help)");
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
    throw UsageError("usage: " + command_line(spec) + " " + spec.usage + " (see " + command_line(spec) + " --help)");
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
  } catch (const std::exception&) {
    const ErrorOutcome e = current_error_outcome();
    const bool input = e.exit == ExitCode::kBadInput;
    std::cerr << program << ": " << (input ? "error: " : "") << e.message << "\n";
    return input ? bad_input : static_cast<int>(e.exit);
  }
}

}  // namespace qf::cli

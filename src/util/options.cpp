// Checked option reads and the options files' check (options.hpp).
#include "pmpm/util/options.hpp"
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <sys/stat.h>
#include <vector>

namespace pmpm {

namespace {

// The option's full name (prefix included) and its text; *found false when not given.
PetscErrorCode RawValue(PetscOptionItems *items, const char opt[], std::string &name,
                        const char **value, PetscBool *found) {
  PetscFunctionBeginUser;
  name = std::string("-") + (items->prefix ? items->prefix : "") + (opt + 1);
  PetscCall(PetscOptionsFindPair(items->options, items->prefix, opt, value, found));
  PetscFunctionReturn(0);
}

enum class Parse { Ok, Empty, NotNumber, NonFinite };

Parse ParseReal(const std::string &s) {
  if (s.empty()) return Parse::Empty;
  char *end = nullptr;
  errno = 0;
  const double x = std::strtod(s.c_str(), &end);
  if (end != s.c_str() + s.size()) return Parse::NotNumber;
  // strtod's ERANGE also flags underflow to a subnormal or zero: only overflow (inf) is refused
  if (!std::isfinite(x)) return Parse::NonFinite;
  return Parse::Ok;
}

} // namespace

PetscErrorCode OptionReal(PetscOptionItems *items, const char opt[], const char text[],
                          const char man[], PetscReal current, PetscReal *value, PetscBool *set) {
  std::string name;
  const char *v = nullptr;
  PetscBool found = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCall(RawValue(items, opt, name, &v, &found));
  if (found) {
    const std::string s = v ? v : "";
    const Parse p = ParseReal(s);
    PetscCheck(p != Parse::Empty, items->comm, PETSC_ERR_USER_INPUT,
               "%s needs a value: one real number (%s)", name.c_str(), text);
    PetscCheck(p != Parse::NotNumber, items->comm, PETSC_ERR_USER_INPUT,
               "%s expects one real number, got \"%s\" (%s)", name.c_str(), s.c_str(), text);
    PetscCheck(p != Parse::NonFinite, items->comm, PETSC_ERR_USER_INPUT,
               "%s must be a finite real number, got \"%s\" (%s)", name.c_str(), s.c_str(), text);
  }
  PetscCall(PetscOptionsReal_Private(items, opt, text, man, current, value, set));
  PetscFunctionReturn(0);
}

PetscErrorCode OptionRealArray(PetscOptionItems *items, const char opt[], const char text[],
                               const char man[], PetscReal value[], PetscInt *n, PetscBool *set) {
  std::string name;
  const char *v = nullptr;
  PetscBool found = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCall(RawValue(items, opt, name, &v, &found));
  if (found) {
    const std::string s = v ? v : "";
    PetscCheck(!s.empty(), items->comm, PETSC_ERR_USER_INPUT,
               "%s needs a value: up to %d comma-separated real numbers (%s)", name.c_str(),
               (int)*n, text);
    PetscInt count = 0;
    std::stringstream ss(s);
    std::string tok;
    while (std::getline(ss, tok, ',')) {
      ++count;
      const Parse p = ParseReal(tok);
      PetscCheck(p == Parse::Ok || p == Parse::NonFinite, items->comm, PETSC_ERR_USER_INPUT,
                 "%s expects comma-separated real numbers, got \"%s\" (%s)", name.c_str(),
                 s.c_str(), text);
      PetscCheck(p == Parse::Ok, items->comm, PETSC_ERR_USER_INPUT,
                 "%s must be finite real numbers, got \"%s\" (%s)", name.c_str(), s.c_str(), text);
    }
    PetscCheck(s.back() != ',', items->comm, PETSC_ERR_USER_INPUT,
               "%s expects comma-separated real numbers, got \"%s\" (%s)", name.c_str(), s.c_str(),
               text);
    PetscCheck(count <= *n, items->comm, PETSC_ERR_USER_INPUT,
               "%s takes at most %d values, got %d in \"%s\" (%s)", name.c_str(), (int)*n,
               (int)count, s.c_str(), text);
  }
  PetscCall(PetscOptionsRealArray_Private(items, opt, text, man, value, n, set));
  PetscFunctionReturn(0);
}

PetscErrorCode OptionEnum(PetscOptionItems *items, const char opt[], const char text[],
                          const char man[], const char *const *list, PetscEnum current,
                          PetscEnum *value, PetscBool *set) {
  std::string name;
  const char *v = nullptr;
  PetscBool found = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCall(RawValue(items, opt, name, &v, &found));
  if (found) {
    // the list: the names, then the enum's type name, its prefix and a null
    int n = 0;
    while (list[n]) ++n;
    n -= 2;
    std::string names;
    bool known = false;
    for (int k = 0; k < n; ++k) {
      names += (k ? ", " : "") + std::string(list[k]);
      known = known || (v && strcasecmp(v, list[k]) == 0);
    }
    PetscCheck(known, items->comm, PETSC_ERR_USER_INPUT, "%s %s is unknown; allowed: %s (%s)",
               name.c_str(), v && v[0] ? v : "(no value)", names.c_str(), text);
  }
  PetscCall(PetscOptionsEnum_Private(items, opt, text, man, list, current, value, set));
  PetscFunctionReturn(0);
}

PetscErrorCode OptionInt(PetscOptionItems *items, const char opt[], const char text[],
                         const char man[], PetscInt current, PetscInt *value, PetscBool *set) {
  std::string name;
  const char *v = nullptr;
  PetscBool found = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCall(RawValue(items, opt, name, &v, &found));
  if (found) {
    const std::string s = v ? v : "";
    PetscCheck(!s.empty(), items->comm, PETSC_ERR_USER_INPUT, "%s needs a value: one integer (%s)",
               name.c_str(), text);
    char *end = nullptr;
    errno = 0;
    const long long x = std::strtoll(s.c_str(), &end, 10);
    PetscCheck(end == s.c_str() + s.size(), items->comm, PETSC_ERR_USER_INPUT,
               "%s expects one integer, got \"%s\" (%s)", name.c_str(), s.c_str(), text);
    PetscCheck(errno != ERANGE && x >= PETSC_MIN_INT && x <= PETSC_MAX_INT, items->comm,
               PETSC_ERR_USER_INPUT, "%s is out of the integer range, got \"%s\" (%s)",
               name.c_str(), s.c_str(), text);
  }
  PetscCall(PetscOptionsInt_Private(items, opt, text, man, current, value, set, PETSC_MIN_INT,
                                    PETSC_MAX_INT));
  PetscFunctionReturn(0);
}

namespace {

// PETSc's test for an option name (PetscOptionsValidKey, without PETSc initialised): "-" or "--"
// then a letter, and not a number such as -5 or -1e3.
bool ValidKey(const std::string &k) {
  if (k.size() < 2 || k[0] != '-') return false;
  size_t i = k[1] == '-' ? 2 : 1;
  if (i >= k.size() || !std::isalpha(static_cast<unsigned char>(k[i]))) return false;
  char *end = nullptr;
  (void)std::strtod(k.c_str(), &end);
  if (end != k.c_str() && !(*end == '_' || std::isalnum(static_cast<unsigned char>(*end))))
    return false;
  return true;
}

// A line's tokens: split at blanks, a double-quoted token kept whole.
std::vector<std::string> Tokens(const std::string &line) {
  std::vector<std::string> t;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i >= line.size()) break;
    std::string tok;
    if (line[i] == '"') {
      const size_t j = line.find('"', i + 1);
      tok = line.substr(i + 1, j == std::string::npos ? std::string::npos : j - i - 1);
      i = j == std::string::npos ? line.size() : j + 1;
    } else {
      while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i])))
        tok += line[i++];
    }
    t.push_back(tok);
  }
  return t;
}

constexpr int kMaxDepth = 16;

std::string CheckFile(const std::string &file, std::vector<std::string> &stack) {
  const std::string from =
      stack.empty() ? "given to -options_file" : "included by options file " + stack.back();
  struct stat st;
  if (stat(file.c_str(), &st) != 0)
    return "cannot open options file " + file + " (" + from +
           "; paths are relative to the current directory): " + std::strerror(errno);
  if (S_ISDIR(st.st_mode))
    return "options file " + file + " is a directory (" + from + "): give an options file";
  char *real = realpath(file.c_str(), nullptr);
  const std::string key = real ? real : file;
  std::free(real);
  for (const std::string &s : stack) {
    char *r = realpath(s.c_str(), nullptr);
    const bool same = key == (r ? r : s);
    std::free(r);
    if (same) {
      std::string chain;
      for (const std::string &t : stack) chain += t + " -> ";
      return "options file " + file + " includes itself (-options_file " + chain + file +
             "): remove the -options_file line that closes the cycle";
    }
  }
  if ((int)stack.size() >= kMaxDepth)
    return "options file " + file + " is nested more than " + std::to_string(kMaxDepth) +
           " -options_file levels deep (" + from + ")";
  std::ifstream in(file, std::ios::binary);
  if (!in) return "cannot read options file " + file + " (" + from + ")";
  std::string line;
  int lineno = 0;
  stack.push_back(file);
  while (std::getline(in, line)) {
    ++lineno;
    const std::string where = "options file " + file + " line " + std::to_string(lineno);
    if (line.find('\0') != std::string::npos)
      return where + ": not text (each line: -option [value], or # comment)";
    const size_t hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    const std::vector<std::string> t = Tokens(line);
    if (t.empty()) continue;
    if (t[0] == "alias") {
      if (t.size() != 3) return where + ": alias needs two option names (alias -new -old)";
      continue;
    }
    if (!ValidKey(t[0]))
      return where + ": \"" + t[0] +
             "\" is not an option name (each line: -option [value], or # comment)";
    if (t.size() > 1 && ValidKey(t[1]))
      return where + ": two options on one line (" + t[0] + " " + t[1] + "); one per line";
    if (t.size() > 2)
      return where + ": " + t[0] + " with more than one value (\"" + t[1] + " " + t[2] +
             "\"); a list is comma-separated, without blanks";
    if (strcasecmp(t[0].c_str(), "-options_file") == 0) {
      if (t.size() < 2) return where + ": -options_file needs a file name";
      const std::string err = CheckFile(t[1], stack);
      if (!err.empty()) return err;
    }
  }
  stack.pop_back();
  return "";
}

} // namespace

std::string CheckOptionsFiles(int argc, char **argv) {
  for (int i = 1; i < argc; ++i) {
    if (strcasecmp(argv[i], "-options_file") != 0) continue;
    if (i + 1 >= argc || ValidKey(argv[i + 1]))
      return "-options_file needs a file name (-options_file options/<scene>.opts)";
    std::vector<std::string> stack;
    const std::string err = CheckFile(argv[i + 1], stack);
    if (!err.empty()) return err;
    ++i;
  }
  return "";
}

} // namespace pmpm

namespace pmpm {

bool ListingHelp() {
  PetscBool help = PETSC_FALSE;
  if (PetscOptionsHasHelp(nullptr, &help)) return false;
  return help == PETSC_TRUE;
}

PetscErrorCode CheckCells(MPI_Comm comm, const char *option, double length, double h,
                          PetscInt *cells) {
  PetscFunctionBeginUser;
  const double r = length / h;
  PmpmCheckInput(length > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "%s must be > 0 (got %g)", option,
                 length);
  PmpmCheckInput(
      std::fabs(r - std::round(r)) < 1e-6 * std::fmax(1.0, r) && std::round(r) >= 1, comm,
      PETSC_ERR_ARG_OUTOFRANGE,
      "%s = %g m is not a whole number (>= 1) of cells of -cell_size %g m: the grid is too "
      "coarse for the body or misaligned with it",
      option, length, h);
  *cells = static_cast<PetscInt>(std::round(r));
  PetscFunctionReturn(0);
}

} // namespace pmpm

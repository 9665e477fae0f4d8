// The option tables' parser, their usage text and the commands' exit codes (see command_args.h).
#include "app/command_args.h"

#include <algorithm>
#include <iostream>
#include <new>
#include <sstream>

#include "core/mesh/input_error.h"

namespace polarview {

int parseIntArgument(const std::string& option, const std::string& text, int low, int high) {
  size_t used = 0;
  long value = 0;
  try {
    value = std::stol(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (text.empty() || used != text.size() || value < low || value > high)
    throw UsageError(option + " expects an integer in " + std::to_string(low) + ".." + std::to_string(high) + ", got '" +
                     text + "'");
  return int(value);
}

// [SECTION] Row makers

OptionRow flagOption(std::vector<std::string> names, std::string help, bool* target, bool value) {
  return {std::move(names), "", std::move(help), false, [target, value](const std::string&) { *target = value; }};
}

OptionRow textOption(std::vector<std::string> names, std::string metavar, std::string help, std::string* target) {
  return {std::move(names), std::move(metavar), std::move(help), false, [target](const std::string& v) { *target = v; }};
}

OptionRow intOption(std::vector<std::string> names, std::string metavar, std::string help, int* target, int low,
                    int high) {
  const std::string name = names.front();
  return {std::move(names), std::move(metavar), std::move(help), false,
          [=](const std::string& v) { *target = parseIntArgument(name, v, low, high); }};
}

OptionRow intOption(std::vector<std::string> names, std::string metavar, std::string help, std::optional<int>* target,
                    int low, int high) {
  const std::string name = names.front();
  return {std::move(names), std::move(metavar), std::move(help), false,
          [=](const std::string& v) { *target = parseIntArgument(name, v, low, high); }};
}

OptionRow listOption(std::vector<std::string> names, std::string metavar, std::string help,
                     std::vector<std::string>* target) {
  const std::string name = names.front();
  return {std::move(names), std::move(metavar), std::move(help), false, [=](const std::string& v) {
            std::stringstream list(v);
            std::string item;
            while (std::getline(list, item, ','))
              if (!item.empty()) target->push_back(item);
            if (v.empty() || v.find_first_not_of(',') == std::string::npos) throw UsageError(name + " needs a value");
          }};
}

OptionRow actionOption(std::vector<std::string> names, std::string metavar, std::string help,
                       std::function<void(const std::string&)> store) {
  return {std::move(names), std::move(metavar), std::move(help), false, std::move(store)};
}

OptionRow positionalOption(std::string metavar, std::string help, std::string* target) {
  return {{}, std::move(metavar), std::move(help), false, [target](const std::string& v) { *target = v; }};
}

OptionRow supersampleOption(int* target) {
  return {{"--supersample"}, "1|2|4", "draw 1, 2 or 4 times larger, then scale down (default " + std::to_string(*target) + ")",
          false, [target](const std::string& v) {
            *target = parseIntArgument("--supersample", v, 1, 4);
            if (*target == 3) throw UsageError("--supersample takes 1, 2 or 4, got 3");
          }};
}

OptionRow required(OptionRow row) {
  row.required = true;
  return row;
}

// [SECTION] Parsing

namespace {

// How a row reads in usage: "-o OUT.obj", "--json", "IN.obj".
std::string rowSynopsis(const OptionRow& row) {
  if (row.names.empty()) return row.metavar;
  return row.metavar.empty() ? row.names.front() : row.names.front() + " " + row.metavar;
}

bool isOptionWord(const std::string& word) { return word.size() > 1 && word[0] == '-'; }

}  // namespace

void parseOptions(const OptionTable& table, const Args& args) {
  std::vector<bool> given(table.size(), false);
  const auto positional = std::find_if(table.begin(), table.end(), [](const OptionRow& r) { return r.names.empty(); });
  for (size_t k = 0; k < args.size(); ++k) {
    const std::string& word = args[k];
    if (word == "-h" || word == "--help") throw HelpRequest{};
    if (!isOptionWord(word)) {
      if (positional == table.end() || given[size_t(positional - table.begin())])
        throw UsageError("unexpected argument '" + word + "'");
      given[size_t(positional - table.begin())] = true;
      positional->store(word);
      continue;
    }
    const auto row = std::find_if(table.begin(), table.end(), [&](const OptionRow& r) {
      return std::find(r.names.begin(), r.names.end(), word) != r.names.end();
    });
    if (row == table.end()) throw UsageError("unknown option '" + word + "'");
    given[size_t(row - table.begin())] = true;
    if (row->metavar.empty()) {
      row->store("");
      continue;
    }
    if (k + 1 >= args.size()) throw UsageError(word + " needs a value");
    row->store(args[++k]);
  }
  for (size_t r = 0; r < table.size(); ++r)
    if (table[r].required && !given[r]) throw UsageError("needs " + rowSynopsis(table[r]));
}

// [SECTION] Usage text

std::string commandSynopsis(const std::string& name, const OptionTable& table) {
  constexpr size_t kWidth = 100;
  const std::string indent(std::string("polarview ").size() + name.size() + 1, ' ');
  std::string text = "polarview " + name, line = text;
  // The positional argument first, then the required options, then the rest in table order.
  std::vector<std::string> words;
  for (int pass = 0; pass < 3; ++pass)
    for (const OptionRow& row : table) {
      const int rank = row.names.empty() ? 0 : row.required ? 1 : 2;
      if (rank != pass) continue;
      words.push_back(row.required ? rowSynopsis(row) : "[" + rowSynopsis(row) + "]");
    }
  for (const std::string& word : words) {
    if (line.size() + 1 + word.size() > kWidth && line.size() > indent.size()) {
      text += "\n" + indent;
      line = indent;
    } else {
      text += " ";
      line += " ";
    }
    text += word;
    line += word;
  }
  return text + "\n";
}

std::string commandHelp(const std::string& name, const OptionTable& table) {
  std::vector<std::string> heads;
  size_t width = 0;
  for (const OptionRow& row : table) {
    std::string head;
    for (const std::string& n : row.names) head += (head.empty() ? "" : ", ") + n;
    if (!row.metavar.empty()) head += (head.empty() ? "" : " ") + row.metavar;
    width = std::max(width, head.size());
    heads.push_back(head);
  }
  // Help texts wrap at 100 columns, under their own column.
  constexpr size_t kWidth = 100;
  const std::string indent(4 + width + 2, ' ');
  std::string text = commandSynopsis(name, table);
  for (size_t r = 0; r < table.size(); ++r) {
    std::string line = "    " + heads[r] + std::string(width + 2 - heads[r].size(), ' ');
    std::istringstream words(table[r].help);
    std::string word;
    bool first = true;
    while (words >> word) {
      if (!first && line.size() + 1 + word.size() > kWidth) {
        text += line + "\n";
        line = indent;
        first = true;
      }
      line += (first ? "" : " ") + word;
      first = false;
    }
    text += line + "\n";
  }
  return text;
}

// [SECTION] Exit codes

int runGuarded(const std::string& name, const CommandParser& command, const Args& args, FailureSubject subject) {
  const std::string file = subject == FailureSubject::FirstArgument && !args.empty() && !args[0].empty() ? args[0]
                                                                                                        : "<input>";
  const std::string prefix = subject == FailureSubject::None ? "" : file + ": ";
  try {
    return command.parseAndRun(args);
  } catch (const HelpRequest&) {
    std::cout << "usage: " << commandHelp(name, command.table());
    return 0;
  } catch (const UsageError& e) {
    std::cerr << "polarview: " << name << ": " << e.what() << "\nusage: " << commandHelp(name, command.table());
    return 2;
  } catch (const InputError& e) {
    std::cerr << "polarview: " << e.what() << "\n";
    return 1;
  } catch (const std::bad_alloc& e) {
    std::cerr << "polarview: " << (subject == FailureSubject::None ? std::string(e.what()) : prefix + "out of memory")
              << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "polarview: " << prefix << e.what() << "\n";
    return 1;
  }
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace polarview

// SPDX-License-Identifier: MIT
#include "pddl_sim.h"

#include <memory>
#include <stdexcept>

namespace sewerplan::testing {
namespace {

std::string lower(std::string s) {
  for (char& c : s) {
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  }
  return s;
}

struct Node {
  std::string atom;  // empty for a list
  std::vector<Node> items;
  bool is_list() const { return atom.empty(); }
};

class Reader {
 public:
  explicit Reader(const std::string& text) : text_(text) {}
  Node read() {
    skip();
    if (pos_ >= text_.size()) throw std::runtime_error("PDDL: unexpected end");
    if (text_[pos_] == '(') {
      ++pos_;
      Node list;
      for (skip(); pos_ < text_.size() && text_[pos_] != ')'; skip()) list.items.push_back(read());
      if (pos_ >= text_.size()) throw std::runtime_error("PDDL: missing ')'");
      ++pos_;
      return list;
    }
    const std::size_t start = pos_;
    while (pos_ < text_.size() && !std::isspace(static_cast<unsigned char>(text_[pos_])) &&
           text_[pos_] != '(' && text_[pos_] != ')' && text_[pos_] != ';') {
      ++pos_;
    }
    if (pos_ == start) throw std::runtime_error("PDDL: stray ')'");
    return Node{lower(text_.substr(start, pos_ - start)), {}};
  }

 private:
  void skip() {
    while (pos_ < text_.size()) {
      if (text_[pos_] == ';') {
        while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
      } else if (std::isspace(static_cast<unsigned char>(text_[pos_]))) {
        ++pos_;
      } else {
        break;
      }
    }
  }
  const std::string& text_;
  std::size_t pos_ = 0;
};

// "a b - t c - u" -> {(a, t), (b, t), (c, u)}; untyped names are objects.
std::vector<std::pair<std::string, std::string>> typed_list(const std::vector<Node>& items,
                                                            std::size_t from) {
  std::vector<std::pair<std::string, std::string>> out;
  std::vector<std::string> pending;
  for (std::size_t i = from; i < items.size(); ++i) {
    if (items[i].atom == "-" && i + 1 < items.size()) {
      for (auto& name : pending) out.emplace_back(name, items[i + 1].atom);
      pending.clear();
      ++i;
    } else {
      pending.push_back(items[i].atom);
    }
  }
  for (auto& name : pending) out.emplace_back(name, "object");
  return out;
}

std::vector<std::string> atom_tokens(const Node& n) {
  std::vector<std::string> out;
  for (const Node& item : n.items) out.push_back(item.atom);
  return out;
}

// The atoms of a conjunction; (not X) go to `negated`; numeric effects are skipped.
void conjuncts(const Node& n, std::vector<std::vector<std::string>>& positive,
               std::vector<std::vector<std::string>>* negated) {
  if (!n.is_list() || n.items.empty()) return;
  const std::string& head = n.items.front().atom;
  if (head == "and") {
    for (std::size_t i = 1; i < n.items.size(); ++i) conjuncts(n.items[i], positive, negated);
  } else if (head == "not") {
    if (!negated) throw std::runtime_error("PDDL: negative precondition");
    negated->push_back(atom_tokens(n.items.at(1)));
  } else if (head != "increase" && head != "=") {
    positive.push_back(atom_tokens(n));
  }
}

std::string join(const std::vector<std::string>& tokens) {
  std::string out = "(";
  for (std::size_t i = 0; i < tokens.size(); ++i) out += (i ? " " : "") + tokens[i];
  return out + ")";
}

}  // namespace

PddlSim::PddlSim(const std::string& domain, const std::string& problem) {
  const Node d = Reader(domain).read();
  for (const Node& section : d.items) {
    if (!section.is_list() || section.items.empty()) continue;
    const std::string& head = section.items.front().atom;
    if (head == ":types") {
      for (auto& [type, parent] : typed_list(section.items, 1)) parent_type_[type] = parent;
    } else if (head == ":action") {
      Action action;
      const std::string name = section.items.at(1).atom;
      for (std::size_t i = 2; i + 1 < section.items.size(); i += 2) {
        const std::string& key = section.items[i].atom;
        const Node& value = section.items[i + 1];
        if (key == ":parameters") action.parameters = typed_list(value.items, 0);
        if (key == ":precondition") conjuncts(value, action.pre, nullptr);
        if (key == ":effect") conjuncts(value, action.add, &action.del);
      }
      actions_[name] = action;
    }
  }
  const Node p = Reader(problem).read();
  for (const Node& section : p.items) {
    if (!section.is_list() || section.items.empty()) continue;
    const std::string& head = section.items.front().atom;
    if (head == ":objects") {
      for (auto& [object, type] : typed_list(section.items, 1)) object_type_[object] = type;
    } else if (head == ":init") {
      for (std::size_t i = 1; i < section.items.size(); ++i) {
        if (section.items[i].items.front().atom != "=") {
          state_.insert(join(atom_tokens(section.items[i])));
        }
      }
    } else if (head == ":goal") {
      std::vector<std::vector<std::string>> atoms;
      conjuncts(section.items.at(1), atoms, nullptr);
      for (auto& atom : atoms) goal_.push_back(join(atom));
    }
  }
}

bool PddlSim::is_a(const std::string& object, const std::string& type) const {
  auto found = object_type_.find(object);
  if (found == object_type_.end()) return false;
  for (std::string t = found->second;;) {
    if (t == type) return true;
    auto parent = parent_type_.find(t);
    if (parent == parent_type_.end() || parent->second == t) return type == "object";
    t = parent->second;
  }
}

std::optional<std::string> PddlSim::apply(const std::string& action_name,
                                          const std::vector<std::string>& raw_args) {
  auto found = actions_.find(lower(action_name));
  if (found == actions_.end()) return "no action " + action_name;
  const Action& action = found->second;
  if (raw_args.size() != action.parameters.size()) return "wrong number of arguments";
  std::map<std::string, std::string> binding;
  for (std::size_t i = 0; i < raw_args.size(); ++i) {
    const std::string arg = lower(raw_args[i]);
    if (!is_a(arg, action.parameters[i].second)) {
      return arg + " is not a " + action.parameters[i].second;
    }
    binding[action.parameters[i].first] = arg;
  }
  auto ground = [&](std::vector<std::string> atom) {
    for (std::string& token : atom) {
      if (auto b = binding.find(token); b != binding.end()) token = b->second;
    }
    return join(atom);
  };
  for (const auto& atom : action.pre) {
    if (!state_.count(ground(atom))) return "precondition " + ground(atom) + " is false";
  }
  for (const auto& atom : action.del) state_.erase(ground(atom));
  for (const auto& atom : action.add) state_.insert(ground(atom));
  return std::nullopt;
}

bool PddlSim::goal_reached() const {
  for (const std::string& atom : goal_) {
    if (!state_.count(atom)) return false;
  }
  return true;
}

}  // namespace sewerplan::testing

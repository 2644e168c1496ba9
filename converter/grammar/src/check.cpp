// The checks of a parsed grammar (check.hpp).
#include "check.hpp"

#include <map>
#include <set>
#include <vector>

#include "lexer.hpp"

namespace nut::grammar {

namespace {

bool isTerminal(Op op) {
  return op == Op::Material || op == Op::Generate || op == Op::Discard || op == Op::Skip || op == Op::SkipMask;
}

// The rules from which every derivation ends in terminals: a terminal, or a rule all of whose
// successors are such rules (a random choice may take any of them).
std::set<std::string> terminating(const Grammar& g) {
  std::set<std::string> done;
  for (bool grew = true; grew;) {
    grew = false;
    for (const Rule& r : g.rules) {
      if (done.count(r.name)) continue;
      bool all = true;
      for (const Part& p : r.parts) all = all && (done.count(p.rule) || (isEmptyName(p.rule) && !g.find(p.rule)));
      if (isTerminal(r.op) || all) grew = done.insert(r.name).second || grew;
    }
  }
  return done;
}

// The loop a rule that never ends leads into: from `from`, each step to a successor that does not
// end either (there is one: a rule whose successors all end, ends) until a rule comes again. The
// loop is returned from that rule, "D -> E -> D".
std::vector<const Rule*> loopFrom(const Grammar& g, const Rule* from, const std::set<std::string>& ends) {
  std::vector<const Rule*> path{from};
  while (true) {
    const Rule* next = nullptr;
    for (const Part& p : path.back()->parts)
      if (!ends.count(p.rule) && g.find(p.rule)) next = g.find(p.rule);
    for (std::size_t k = 0; k < path.size(); ++k)
      if (path[k] == next) {
        std::vector<const Rule*> loop(path.begin() + static_cast<std::ptrdiff_t>(k), path.end());
        loop.push_back(next);
        return loop;
      }
    path.push_back(next);
  }
}

}  // namespace

Status checkGrammar(Grammar& g, const std::string& start, const Position& startAt) {
  if (g.rules.empty()) return Error{g.file + ": no rules"};
  std::map<std::string, const Rule*> byName;
  for (const Rule& r : g.rules) {
    auto [it, added] = byName.emplace(r.name, &r);
    if (!added)
      return Error{where(g.file, r.at) + "rule '" + r.name + "' is defined twice (first on line " +
                   std::to_string(it->second->at.line) + ")"};
  }
  std::set<std::string> named;  // by another rule
  for (const Rule& r : g.rules)
    for (const Part& p : r.parts) {
      if (!byName.count(p.rule) && !isEmptyName(p.rule))
        return Error{where(g.file, p.at) + "no rule '" + p.rule + "' (" + r.name + " names it)"};
      if (p.rule != r.name) named.insert(p.rule);
    }

  if (!start.empty()) {
    if (!byName.count(start))
      return Error{(startAt.line > 0 ? where(g.file, startAt) : g.file + ": ") + "no start rule '" + start + "'"};
    g.start = start;
  } else {
    std::vector<const Rule*> candidates;
    for (const Rule& r : g.rules)
      if (!named.count(r.name)) candidates.push_back(&r);
    if (candidates.empty())
      return Error{g.file + ": every rule is named by another, so none is the start; name it with @start or --start"};
    if (candidates.size() > 1) {
      std::string list;
      for (const Rule* r : candidates)
        list += (list.empty() ? "" : ", ") + r->name + " (line " + std::to_string(r->at.line) + ")";
      return Error{g.file + ": several rules are named by no other: " + list +
                   "; choose the start with @start or --start"};
    }
    g.start = candidates.front()->name;
  }

  // Every rule the start reaches must end in terminals.
  const std::set<std::string> ends = terminating(g);
  std::set<std::string> reached{g.start};
  std::vector<std::string> stack{g.start};
  while (!stack.empty()) {
    const Rule* r = byName[stack.back()];
    stack.pop_back();
    if (!ends.count(r->name)) {
      const std::vector<const Rule*> loop = loopFrom(g, r, ends);
      std::string names;
      for (const Rule* l : loop) names += (names.empty() ? "" : " -> ") + l->name;
      return Error{where(g.file, loop.front()->at) + "rule '" + loop.front()->name + "' never reaches a terminal (" +
                   names + ")"};
    }
    for (const Part& p : r->parts)
      if (byName.count(p.rule) && reached.insert(p.rule).second) stack.push_back(p.rule);
  }
  return Ok{};
}

}  // namespace nut::grammar

#include <spirv-tools/optimizer.hpp>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <unordered_map>
#include <vector>
using namespace spvtools;
struct Entry { std::vector<uint32_t> m; std::unordered_map<uint32_t, std::vector<uint32_t>> v; std::string name; };
std::vector<uint32_t> run(const Entry& e, const std::vector<std::string>* flags, double& ms) {
  auto t0 = std::chrono::steady_clock::now();
  Optimizer opt(SPV_ENV_VULKAN_1_2);
  opt.SetMessageConsumer([](spv_message_level_t, const char*, const spv_position_t&, const char*) {});
  opt.RegisterPass(CreateSetSpecConstantDefaultValuePass(e.v)).RegisterPass(CreateFreezeSpecConstantValuePass())
     .RegisterPass(CreateFoldSpecConstantOpAndCompositePass()).RegisterPass(CreateDeadBranchElimPass())
     .RegisterPass(CreateAggressiveDCEPass()).RegisterPass(CreateBlockMergePass())
     .RegisterPass(CreateEliminateDeadFunctionsPass()).RegisterPass(CreateAggressiveDCEPass());
  if (!flags) opt.RegisterPerformancePasses();
  else for (auto& f : *flags) if (!opt.RegisterPassFromFlag(f)) { std::cerr << "bad flag " << f << "\n"; exit(1); }
  OptimizerOptions o; o.set_run_validator(false);
  std::vector<uint32_t> out;
  if (!opt.Run(e.m.data(), e.m.size(), &out, o)) out.clear();
  ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return out;
}
int main(int argc, char** argv) {
  std::vector<Entry> es;
  for (auto& p : std::filesystem::directory_iterator(argv[1])) {
    if (p.path().extension() != ".spv") continue;
    Entry e; e.name = p.path().stem();
    std::ifstream f(p.path(), std::ios::binary); std::vector<char> b((std::istreambuf_iterator<char>(f)), {});
    e.m.resize(b.size() / 4); std::memcpy(e.m.data(), b.data(), b.size());
    auto sp = p.path(); sp.replace_extension(".spec"); std::ifstream s(sp); std::string tok;
    while (s >> tok) { auto c = tok.find(':'); e.v[std::stoul(tok.substr(0, c))] = {uint32_t(std::stoul(tok.substr(c + 1)))}; }
    es.push_back(e);
  }
  // reference
  std::vector<std::vector<uint32_t>> ref; double tref = 0;
  for (auto& e : es) { double ms; ref.push_back(run(e, nullptr, ms)); tref += ms; }
  std::printf("reference: %.0f ms\n", tref);
  if (argc > 2 && std::string(argv[2]) == "greedy") {
    std::string line; std::getline(std::cin, line);
    std::istringstream is(line); std::vector<std::string> flags; std::string f; while (is >> f) flags.push_back(f);
    auto eval = [&](const std::vector<std::string>& fl, double& t) { t = 0; bool ok = true;
      for (size_t i = 0; i < es.size(); ++i) { double ms; auto o = run(es[i], &fl, ms); t += ms; ok &= o == ref[i]; } return ok; };
    double tcur; eval(flags, tcur);
    std::printf("start %.0f ms\n", tcur);
    for (size_t i = 0; i < flags.size();) {
      auto trial = flags; trial.erase(trial.begin() + i);
      double t; bool ok = eval(trial, t);
      std::printf("drop %zu %s: %s %.0f ms\n", i, flags[i].c_str(), ok ? "same" : "differs", t); std::fflush(stdout);
      if (ok) { flags = trial; tcur = t; } else ++i;
    }
    std::printf("final %.0f ms:", tcur); for (auto& x : flags) std::printf(" %s", x.c_str()); std::printf("\n");
    return 0;
  }
  // recipes from stdin: one per line, flags separated by spaces
  std::string line;
  while (std::getline(std::cin, line)) {
    if (line.empty()) continue;
    std::istringstream is(line); std::vector<std::string> flags; std::string f; while (is >> f) flags.push_back(f);
    double t = 0; int same = 0; size_t bytes = 0, refbytes = 0;
    for (size_t i = 0; i < es.size(); ++i) { double ms; auto o = run(es[i], &flags, ms); t += ms; same += o == ref[i]; bytes += o.size() * 4; refbytes += ref[i].size() * 4; }
    std::printf("%.0f ms, %d/%zu identical, %zu vs %zu bytes: %s\n", t, same, es.size(), bytes, refbytes, line.substr(0, 120).c_str());
    std::fflush(stdout);
  }
}

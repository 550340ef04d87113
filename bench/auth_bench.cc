// The cost of authenticating a command (common/message_auth.h; common/node/README.md,
// "Security"): median CPU time to sign and to verify one message, for a DRIVE_COMMAND (the
// tracker's 10 Hz command) and a PATH of 100 segments (the largest signed message the fleet
// sends), and the bytes the trailer adds.
//
//   auth_bench [--quick] [--json-out FILE]

#include <cstdio>
#include <string>
#include <vector>

#include "bench/bench_util.h"
#include "common/message_auth.h"
#include "common/node/conversions.h"
#include "minenav/drive_command_t.hpp"
#include "minenav/path_t.hpp"

namespace minenav {
namespace {

struct Row {
  std::string message;
  int bytes = 0;
  double sign_ns = 0.0, verify_ns = 0.0;
};

// Median over `batches` of the mean time of `per_batch` calls of `fn`, in ns.
template <typename Fn>
double MedianNs(int batches, int per_batch, Fn fn) {
  std::vector<double> ns;
  for (int b = 0; b < batches; ++b) {
    const double t0 = bench::Now();
    for (int i = 0; i < per_batch; ++i) fn();
    ns.push_back((bench::Now() - t0) * 1e9 / per_batch);
  }
  return bench::Median(ns);
}

Row Measure(const std::string& name, const std::string& channel, const std::vector<uint8_t>& payload, int batches) {
  constexpr int kPerBatch = 200;
  const AuthKeyRing keys{{RandomAuthKey(1)}};
  MessageSigner signer(RandomSenderId());
  const int64_t now = 1'700'000'000'000'000;
  std::vector<uint8_t> last;
  Row row;
  row.message = name;
  row.bytes = static_cast<int>(payload.size());
  row.sign_ns = MedianNs(batches, kPerBatch, [&] {
    last = signer.Sign(keys, channel, payload.data(), static_cast<int>(payload.size()), now);
  });
  // Every verification a fresh, valid message (a replay would stop early): signed beforehand.
  std::vector<std::vector<uint8_t>> signed_messages;
  for (int i = 0; i < batches * kPerBatch; ++i)
    signed_messages.push_back(signer.Sign(keys, channel, payload.data(), static_cast<int>(payload.size()), now));
  MessageVerifier verifier(5'000'000);
  size_t next = 0;
  int accepted = 0;
  row.verify_ns = MedianNs(batches, kPerBatch, [&] {
    const std::vector<uint8_t>& m = signed_messages[next++];
    accepted += verifier.Verify(keys, channel, m.data(), static_cast<int>(m.size()), now).result ==
                AuthResult::kAccepted;
  });
  if (accepted != batches * kPerBatch) throw std::runtime_error("a valid message was refused");
  return row;
}

int Run(int argc, char** argv) {
  const bench::BenchArgs args = bench::ParseBenchArgs(argc, argv, "auth_bench [--quick] [--json-out FILE]");
  const int batches = args.quick ? 20 : 200;
  drive_command_t drive{};
  drive.utime = 1;
  drive.mode = drive_command_t::VELOCITY;
  drive.v = 0.076;
  drive.timeout = 0.5;
  path_t path{};
  path.feasible = true;
  path.status = "ok";
  path.num_segments = 100;
  path.segments.resize(100);
  std::vector<Row> rows = {Measure("DRIVE_COMMAND", "DRIVE_COMMAND", EncodeMessage(drive), batches),
                           Measure("PATH (100 segments)", "DRIVE_PATH", EncodeMessage(path), batches)};
  std::printf("%-22s %8s %9s %10s %12s\n", "message", "bytes", "+trailer", "sign (ns)", "verify (ns)");
  nlohmann::json out = {{"bench", "auth_bench"}, {"trailer_bytes", kAuthTrailerBytes}, {"batches", batches}};
  for (const Row& r : rows) {
    std::printf("%-22s %8d %9d %10.0f %12.0f\n", r.message.c_str(), r.bytes, kAuthTrailerBytes, r.sign_ns,
                r.verify_ns);
    out["messages"].push_back(
        {{"message", r.message}, {"bytes", r.bytes}, {"sign_ns_median", r.sign_ns}, {"verify_ns_median", r.verify_ns}});
  }
  bench::WriteJson(args.json_out, out);
  return 0;
}

}  // namespace
}  // namespace minenav

int main(int argc, char** argv) { return minenav::bench::RunBenchMain("auth_bench", minenav::Run, argc, argv); }

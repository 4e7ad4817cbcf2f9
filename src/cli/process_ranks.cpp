// One process as ProcessRanks, and the agreement of all ranks on a step's outcome
// (process_ranks.hpp; issue 19, item 6).
#include "process_ranks.hpp"

#include <string>

#include "talus/core/byte_stream.hpp"
#include "talus/core/progress.hpp"

namespace talus::cli {
namespace {

class SingleProcess final : public ProcessRanks {
 public:
  int rank() const override { return 0; }
  int size() const override { return 1; }
  std::vector<std::vector<std::uint8_t>> gather(const std::vector<std::uint8_t>& bytes) const override { return {bytes}; }
  std::vector<std::uint8_t> broadcast(const std::vector<std::uint8_t>& bytes) const override { return bytes; }
};

// What a rank says of its step: nothing (done), or the kind of error and its words.
enum class Outcome : std::uint8_t { done, input, numerical, cancelled, other };

struct Failure {
  Outcome kind = Outcome::done;
  std::string message;
};

std::vector<std::uint8_t> encode(const Failure& f) {
  ByteWriter out;
  out.put(f.kind);
  out.put_vector(std::vector<char>(f.message.begin(), f.message.end()));
  return out.take();
}

Failure decode(const std::vector<std::uint8_t>& bytes) {
  ByteReader in(bytes);
  Failure f;
  f.kind = in.get<Outcome>();
  std::vector<char> text;
  in.get_vector(text);
  f.message.assign(text.begin(), text.end());
  return f;
}

Failure run_step(const std::function<void()>& step) {
  try {
    step();
    return {};
  } catch (const InputError& e) {
    return {Outcome::input, e.what()};
  } catch (const NumericalFailure& e) {
    return {Outcome::numerical, e.what()};
  } catch (const Cancelled& e) {
    return {Outcome::cancelled, e.what()};
  } catch (const std::exception& e) {
    return {Outcome::other, e.what()};
  }
}

// Of the ranks' outcomes (in rank order), the one every rank throws: the lowest rank's failure.
Failure first_failure(const std::vector<std::vector<std::uint8_t>>& outcomes) {
  for (const auto& bytes : outcomes) {
    Failure f = decode(bytes);
    if (f.kind != Outcome::done) return f;
  }
  return {};
}

[[noreturn]] void throw_failure(const Failure& f) {
  switch (f.kind) {
    case Outcome::input:
      throw InputError(f.message);
    case Outcome::numerical:
      throw NumericalFailure(f.message);
    case Outcome::cancelled:
      throw Cancelled();
    case Outcome::done:
    case Outcome::other:
      break;
  }
  throw std::runtime_error(f.message);
}

}  // namespace

const ProcessRanks& single_process() {
  static const SingleProcess one;
  return one;
}

void together(const ProcessRanks& ranks, const std::function<void()>& step) {
  if (ranks.size() == 1) {
    step();
    return;
  }
  const Failure mine = run_step(step);
  const std::vector<std::vector<std::uint8_t>> outcomes = ranks.gather(encode(mine));
  const Failure agreed = decode(ranks.broadcast(ranks.root() ? encode(first_failure(outcomes)) : std::vector<std::uint8_t>{}));
  if (agreed.kind != Outcome::done) throw_failure(agreed);
}

}  // namespace talus::cli

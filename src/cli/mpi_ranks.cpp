// ProcessRanks over MPI (mpi_ranks.hpp): byte messages in pieces of at most 1 GiB (MPI counts
// are int), rank 0 receiving every rank's in rank order.
#include "mpi_ranks.hpp"

#include <mpi.h>

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

namespace talus::cli {
namespace {

constexpr std::size_t kPiece = std::size_t{1} << 30;

void check(int code, const char* what) {
  if (code != MPI_SUCCESS) throw std::runtime_error(std::string("MPI: ") + what + " failed");
}

void send_bytes(const std::vector<std::uint8_t>& bytes, int to) {
  std::uint64_t size = bytes.size();
  check(MPI_Send(&size, 1, MPI_UINT64_T, to, 0, MPI_COMM_WORLD), "send");
  for (std::size_t at = 0; at < bytes.size(); at += kPiece) {
    const int n = static_cast<int>(std::min(kPiece, bytes.size() - at));
    check(MPI_Send(bytes.data() + at, n, MPI_BYTE, to, 1, MPI_COMM_WORLD), "send");
  }
}

std::vector<std::uint8_t> receive_bytes(int from) {
  std::uint64_t size = 0;
  check(MPI_Recv(&size, 1, MPI_UINT64_T, from, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE), "receive");
  std::vector<std::uint8_t> bytes(size);
  for (std::size_t at = 0; at < bytes.size(); at += kPiece) {
    const int n = static_cast<int>(std::min(kPiece, bytes.size() - at));
    check(MPI_Recv(bytes.data() + at, n, MPI_BYTE, from, 1, MPI_COMM_WORLD, MPI_STATUS_IGNORE), "receive");
  }
  return bytes;
}

class MpiRanks final : public ProcessRanks {
 public:
  MpiRanks(int& argc, char**& argv) {
    int provided = 0;
    check(MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided), "initialisation");
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
  }
  ~MpiRanks() override { MPI_Finalize(); }
  MpiRanks(const MpiRanks&) = delete;
  MpiRanks& operator=(const MpiRanks&) = delete;

  int rank() const override { return rank_; }
  int size() const override { return size_; }

  std::vector<std::vector<std::uint8_t>> gather(const std::vector<std::uint8_t>& bytes) const override {
    if (rank_ != 0) {
      send_bytes(bytes, 0);
      return {};
    }
    std::vector<std::vector<std::uint8_t>> all{bytes};
    for (int from = 1; from < size_; ++from) all.push_back(receive_bytes(from));
    return all;
  }

  std::vector<std::uint8_t> broadcast(const std::vector<std::uint8_t>& bytes) const override {
    std::uint64_t size = bytes.size();
    check(MPI_Bcast(&size, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD), "broadcast");
    std::vector<std::uint8_t> out = rank_ == 0 ? bytes : std::vector<std::uint8_t>(size);
    for (std::size_t at = 0; at < out.size(); at += kPiece) {
      const int n = static_cast<int>(std::min(kPiece, out.size() - at));
      check(MPI_Bcast(out.data() + at, n, MPI_BYTE, 0, MPI_COMM_WORLD), "broadcast");
    }
    return out;
  }

 private:
  int rank_ = 0, size_ = 1;
};

}  // namespace

bool started_by_mpi_launcher() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"}) {
    if (std::getenv(name) != nullptr) return true;
  }
  return false;
}

std::unique_ptr<ProcessRanks> mpi_ranks(int& argc, char**& argv) { return std::make_unique<MpiRanks>(argc, argv); }

}  // namespace talus::cli

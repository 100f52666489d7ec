// The LBM lattice on MPI ranks (docs/scale.md): which rows a rank holds, and the messages that keep
// its halo rows equal to its neighbours' rows at every step. A rank holds rows [row0, row0 + rows)
// (row_slab), two halo rows each side and, with periodic bottom/top sides, one image row (global row
// ny - 1 on rank 0, row 0 on the last rank: the source of the periodic ghosts). Per step and
// neighbour a rank sends its edge row's 9 populations and its two edge rows' depths, 11 cols floats
// (the image partner: 10 cols), and in the wet/dry pass its edge row's outflow limiter theta (cols
// floats) and its second row's populations (9 cols floats: the MUSCL slopes of the HLL faces read
// two rows beyond the slab). The rules, kernels and collisions are those of one process (shallow.cpp).
#include <algorithm>

#include "huygens/lbm/shallow.hpp"

namespace huygens {

namespace {
constexpr int kTagDown = 101, kTagUp = 102, kTagImage = 103;  // populations and depth
constexpr int kThetaDown = 104, kThetaUp = 105, kThetaImage = 106;
constexpr int kSecondDown = 107, kSecondUp = 108;  // the second rows' populations (wet/dry pass)
}  // namespace

void LbmShallow::set_slab(LbmDecomposition d) {
  if (d.ranks < 1 || d.rank < 0 || d.rank >= d.ranks) throw LbmRefused("ranks", "rank outside [0, ranks)");
  ranks_ = d.ranks;
  rank_ = d.rank;
  const RowSlab s = row_slab(static_cast<std::size_t>(p_.rows), ranks_, rank_);
  row0_ = static_cast<int>(s.row0);
  rows_ = static_cast<int>(s.rows);
  if (ranks_ == 1) return;  // one ghost row each side, as ever
  if (p_.rows / ranks_ < 3)
    throw LbmRefused("rows", "the grid's " + std::to_string(p_.rows) + " rows over " + std::to_string(ranks_) +
                                 " ranks leave fewer than 3 rows per rank: run on at most " +
                                 std::to_string(std::max(1, p_.rows / 3)) + " ranks");
  halo_ = 2;
  if (p_.bottom == LbmSide::periodic && (rank_ == 0 || rank_ == ranks_ - 1)) image_row_ = rank_ == 0 ? p_.rows - 1 : 0;
  const std::size_t nx = static_cast<std::size_t>(p_.cols);
  for (int i = 0; i < 2; ++i) {
    send_[i].assign(11 * nx, 0.0f);
    recv_[i].assign(11 * nx, 0.0f);
  }
  if (image_row_ >= 0) {
    send_[2].assign(10 * nx, 0.0f);
    recv_[2].assign(10 * nx, 0.0f);
  }
}

// Neighbour ranks: below (rank - 1), above (rank + 1), periodic image partner; -1 for none.
struct LbmPeers {
  int lo, hi, img;
};

static LbmPeers peers(int rank, int ranks, int image_row) {
  return {rank > 0 ? rank - 1 : -1, rank < ranks - 1 ? rank + 1 : -1, image_row < 0 ? -1 : rank == 0 ? ranks - 1 : 0};
}

void LbmShallow::exchange_halos() {
  start_halos();
  finish_halos();
}

// All wet on several ranks: post the halo messages, update the inner rows (their rules and pulls
// stay inside the slab), complete the messages, then the two edge rows. Each cell's update reads
// only the previous step, so the order changes no bit; the kernel is the one-process kernel.
void LbmShallow::all_wet_overlapped(int& flagged) {
  start_halos();
  int inner = 0, edge = 0;
  std::swap(spans_, inner_spans_);
  std::swap(rules_, inner_rules_);
  {
    StageTimer t(stats_[st_fill_]);
    fill_ghosts(false);
  }
  {
    StageTimer t(stats_[st_kernel_]);
    all_wet_kernel(inner);
  }
  std::swap(spans_, inner_spans_);
  std::swap(rules_, inner_rules_);
  finish_halos();
  std::swap(spans_, edge_spans_);
  std::swap(rules_, edge_rules_);
  {
    StageTimer t(stats_[st_fill_]);
    fill_ghosts(false);
  }
  {
    StageTimer t(stats_[st_kernel_]);
    all_wet_kernel(edge);
  }
  std::swap(spans_, edge_spans_);
  std::swap(rules_, edge_rules_);
  flagged = inner + edge;
}

// Packs this rank's edge rows and posts the messages (the receives first).
void LbmShallow::start_halos() {
  StageTimer t(stats_[st_halo_]);
  const std::size_t nx = static_cast<std::size_t>(p_.cols);
  const LbmPeers peer = peers(rank_, ranks_, image_row_);
  // message: populations of row `edge`, then the depth of `edge` and (neighbours) of `inner`
  auto pack = [&](std::vector<float>& m, int edge, int inner) {
    float* o = m.data();
    for (int a = 0; a < 9; ++a, o += nx) std::copy_n(fa_.data() + a * plane_ + idx(edge, 0), nx, o);
    std::copy_n(ha_.data() + idx(edge, 0), nx, o);
    if (inner >= 0) std::copy_n(ha_.data() + idx(inner, 0), nx, o + nx);
  };
  const int first = row0_, last = row0_ + rows_ - 1;
  if (peer.lo >= 0) xchg_.recv(peer.lo, kTagUp, recv_[0].data(), recv_[0].size());
  if (peer.hi >= 0) xchg_.recv(peer.hi, kTagDown, recv_[1].data(), recv_[1].size());
  if (peer.img >= 0) xchg_.recv(peer.img, kTagImage, recv_[2].data(), recv_[2].size());
  if (peer.lo >= 0) pack(send_[0], first, first + 1), xchg_.send(peer.lo, kTagDown, send_[0].data(), send_[0].size());
  if (peer.hi >= 0) pack(send_[1], last, last - 1), xchg_.send(peer.hi, kTagUp, send_[1].data(), send_[1].size());
  if (peer.img >= 0)
    pack(send_[2], rank_ == 0 ? first : last, -1), xchg_.send(peer.img, kTagImage, send_[2].data(), send_[2].size());
  stats_[st_halo_].sent = xchg_.bytes_sent();
}

// Completes the messages and copies them into the halo rows and the image row.
void LbmShallow::finish_halos() {
  StageTimer t(stats_[st_halo_]);
  const std::size_t nx = static_cast<std::size_t>(p_.cols);
  const LbmPeers peer = peers(rank_, ranks_, image_row_);
  auto unpack = [&](const std::vector<float>& m, int edge, int inner) {
    const float* o = m.data();
    for (int a = 0; a < 9; ++a, o += nx) std::copy_n(o, nx, fa_.data() + a * plane_ + idx(edge, 0));
    std::copy_n(o, nx, ha_.data() + idx(edge, 0));
    if (inner >= 0) std::copy_n(o + nx, nx, ha_.data() + idx(inner, 0));
  };
  xchg_.wait();
  const int first = row0_, last = row0_ + rows_ - 1;
  if (peer.lo >= 0) unpack(recv_[0], first - 1, first - 2);
  if (peer.hi >= 0) unpack(recv_[1], last + 1, last + 2);
  if (peer.img >= 0) unpack(recv_[2], image_row_, -1);
}

void LbmShallow::exchange_theta() {
  if (ranks_ == 1) return;
  StageTimer t(stats_[st_halo_]);
  const std::size_t nx = static_cast<std::size_t>(p_.cols);
  const int lo = rank_ > 0 ? rank_ - 1 : -1, hi = rank_ < ranks_ - 1 ? rank_ + 1 : -1;
  const int img = image_row_ < 0 ? -1 : rank_ == 0 ? ranks_ - 1 : 0;
  const int first = row0_, last = row0_ + rows_ - 1;
  float* theta = theta_.data();
  // the population messages are complete: their buffers carry theta now
  if (lo >= 0) xchg_.recv(lo, kThetaUp, recv_[0].data(), nx);
  if (hi >= 0) xchg_.recv(hi, kThetaDown, recv_[1].data(), nx);
  if (img >= 0) xchg_.recv(img, kThetaImage, recv_[2].data(), nx);
  if (lo >= 0) std::copy_n(theta + idx(first, 0), nx, send_[0].data()), xchg_.send(lo, kThetaDown, send_[0].data(), nx);
  if (hi >= 0) std::copy_n(theta + idx(last, 0), nx, send_[1].data()), xchg_.send(hi, kThetaUp, send_[1].data(), nx);
  if (img >= 0)
    std::copy_n(theta + idx(rank_ == 0 ? first : last, 0), nx, send_[2].data()),
        xchg_.send(img, kThetaImage, send_[2].data(), nx);
  xchg_.wait();
  if (lo >= 0) std::copy_n(recv_[0].data(), nx, theta + idx(first - 1, 0));
  if (hi >= 0) std::copy_n(recv_[1].data(), nx, theta + idx(last + 1, 0));
  if (img >= 0) std::copy_n(recv_[2].data(), nx, theta + idx(image_row_, 0));
  stats_[st_halo_].sent = xchg_.bytes_sent();
}

// The wet/dry pass's MUSCL slopes read the states of the cells two links away: each neighbour
// sends the 9 populations of its second row (9 cols floats; their depth came with the halo
// message), after any unshift of this step, into the second halo row. y-periodic sides on several
// ranks would need a second image row: such a run stops when a cell dries (step()).
void LbmShallow::exchange_second_rows() {
  if (ranks_ == 1) return;
  StageTimer t(stats_[st_halo_]);
  const std::size_t nx = static_cast<std::size_t>(p_.cols);
  const LbmPeers peer = peers(rank_, ranks_, image_row_);
  const int first = row0_, last = row0_ + rows_ - 1;
  auto pack = [&](std::vector<float>& m, int row) {
    for (int a = 0; a < 9; ++a) std::copy_n(fa_.data() + a * plane_ + idx(row, 0), nx, m.data() + a * nx);
  };
  auto unpack = [&](const std::vector<float>& m, int row) {
    for (int a = 0; a < 9; ++a) std::copy_n(m.data() + a * nx, nx, fa_.data() + a * plane_ + idx(row, 0));
  };
  if (peer.lo >= 0) xchg_.recv(peer.lo, kSecondUp, recv_[0].data(), 9 * nx);
  if (peer.hi >= 0) xchg_.recv(peer.hi, kSecondDown, recv_[1].data(), 9 * nx);
  if (peer.lo >= 0) pack(send_[0], first + 1), xchg_.send(peer.lo, kSecondDown, send_[0].data(), 9 * nx);
  if (peer.hi >= 0) pack(send_[1], last - 1), xchg_.send(peer.hi, kSecondUp, send_[1].data(), 9 * nx);
  xchg_.wait();
  if (peer.lo >= 0) unpack(recv_[0], first - 2);
  if (peer.hi >= 0) unpack(recv_[1], last + 2);
  stats_[st_halo_].sent = xchg_.bytes_sent();
}

void LbmShallow::agree(int& flagged, int& bad) {
  if (ranks_ == 1) return;
  StageTimer t(stats_[st_reduce_]);
  double counts[2] = {static_cast<double>(flagged), static_cast<double>(bad)};
  comm::sum(std::span<double>(counts));
  flagged = static_cast<int>(counts[0]);
  bad = static_cast<int>(counts[1]);
}

}  // namespace huygens

#pragma once
// The record behind both winding-number hand-overs across shared input edges
// (EdgeWindings in the leaves, SolidHandover on the solid path): classified
// pieces' edges that lie on an input edge, found by that edge, with the
// winding numbers in front of and behind each piece. The two differ only in
// which neighbours may hand over (their own exactness arguments); what they
// record and how they look it up is this one table.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/model/soup.hpp"

namespace ember::core {

class PieceEdgeTable {
 public:
  /// One edge of a recorded piece on an input edge.
  struct Entry {
    Point from, to;                   ///< the piece's edge, in its own direction
    std::uint32_t source = 0;         ///< the piece's polygon (soup index or triangle id: the caller's)
    std::uint32_t winding = 0;        ///< which stored piece (windings)
    std::uint32_t next = UINT32_MAX;  ///< next entry under the same input edge (recorded earlier)
  };

  /// `expected_edges`: about how many edges will be added (a sizing hint:
  /// the table is made that large once instead of growing by doubling).
  explicit PieceEdgeTable(std::size_t operands, std::size_t expected_edges = 0);

  /// Forgets every recorded piece in O(1); buffers are kept.
  void clear();

  /// Enters edge from -> to of the piece being recorded under the directed
  /// input edge a -> b (in the piece's direction).
  void add_edge(const IntPoint& a, const IntPoint& b, const Point& from, const Point& to, std::uint32_t source);
  /// Stores the winding numbers of the piece whose edges were added since
  /// the last call; false (nothing stored) when none were.
  bool store(const Wnv& front, const Wnv& back);

  /// The most recent entry under the directed input edge a -> b
  /// (UINT32_MAX: none); entry(x).next leads to the earlier ones.
  std::uint32_t first(const IntPoint& a, const IntPoint& b) const;
  const Entry& entry(std::uint32_t x) const { return entries_[x]; }
  /// The front and back winding numbers of stored piece w.
  void windings(std::uint32_t w, Wnv& front, Wnv& back) const;

 private:
  struct Key {
    IntPoint a, b;
    friend bool operator==(const Key&, const Key&) = default;
  };
  struct Slot {
    Key key;
    std::uint32_t head = UINT32_MAX;
    std::uint32_t generation = 0;  ///< the slot is empty unless it equals generation_
  };
  static std::size_t hash(const Key& k);
  std::uint32_t& head_slot(const Key& k);

  std::size_t operands_;
  std::vector<Slot> slots_;  ///< open addressing, power-of-two size, at most half full
  std::size_t used_ = 0;
  std::uint32_t generation_ = 1;
  std::vector<Entry> entries_;
  std::vector<int> windings_;  ///< per stored piece: front then back, operands_ each
  std::uint32_t pieces_ = 0;   ///< stored pieces
  bool pending_ = false;       ///< edges added since the last store
};

}  // namespace ember::core

#pragma once
// Members 0 .. m - 1, each in at most one of a fixed number of doubly linked lists, with the
// links as integer arrays (-1 ends a list): O(1) to add a member at a list's head or to take it
// out, a few integers per list and member (the cell lists of the event-driven engine and the
// buckets of its event calendar).
#include <cstddef>
#include <vector>

namespace granvv::md {

class LinkedLists {
 public:
  // `lists` empty lists for `members` members.
  void reset(std::size_t lists, std::size_t members) {
    head_.assign(lists, -1);
    after_.assign(members, -1);
    before_.assign(members, -1);
  }
  void push_front(std::size_t list, int member) {
    const std::size_t m = std::size_t(member);
    int& head = head_[list];
    before_[m] = -1;
    after_[m] = head;
    if (head >= 0) before_[std::size_t(head)] = member;
    head = member;
  }
  // Takes a member out of the list it is in, `list`.
  void remove(std::size_t list, int member) {
    const std::size_t m = std::size_t(member);
    const int before = before_[m], after = after_[m];
    if (before >= 0) {
      after_[std::size_t(before)] = after;
    } else {
      head_[list] = after;
    }
    if (after >= 0) before_[std::size_t(after)] = before;
  }
  // A list's members: first(list), then next(member) until -1; links() is the array behind
  // next() for loops that walk many lists.
  int first(std::size_t list) const { return head_[list]; }
  int next(int member) const { return after_[std::size_t(member)]; }
  const int* links() const { return after_.data(); }

 private:
  std::vector<int> head_, after_, before_;
};

}  // namespace granvv::md

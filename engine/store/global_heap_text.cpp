#include "engine/store/global_heap_text.hpp"

#include <cstring>

#include "engine/store/h5_detail.hpp"
#include "engine/store/rollback_driver.hpp"

namespace chaosweep {

using h5::Handle;

namespace {

// A collection is at least 4 KiB; one string per run, each rarely longer
// than a line: a few collections hold a whole block's text.
constexpr std::size_t cache_bound = std::size_t(8) << 20;
// The largest collection read (HDF5 makes one per object that does not fit
// an ordinary one): a string of a run's row is far shorter.
constexpr std::uint64_t largest_collection = std::uint64_t(1) << 30;

std::uint64_t le(const unsigned char* p, int n) {
  std::uint64_t v = 0;
  for (int i = n - 1; i >= 0; --i) v = (v << 8) | p[i];
  return v;
}

}  // namespace

GlobalHeapText::GlobalHeapText(hid_t file) : file_(file) {
  Handle fcpl{H5Fget_create_plist(file), H5Pclose};
  hsize_t user_block = 0;
  std::size_t addr_size = 0, length_size = 0;
  if (fcpl.id < 0 || H5Pget_userblock(fcpl.id, &user_block) < 0 || H5Pget_sizes(fcpl.id, &addr_size, &length_size) < 0)
    return;
  base_ = user_block;
  usable_ = addr_size == 8 && length_size == 8;
}

bool GlobalHeapText::text(const unsigned char* e, std::string& out) {
  const std::uint64_t length = le(e, 4), address = le(e + 4, 8), object = le(e + 12, 4);
  if (address == 0) {  // HDF5 writes an empty string (or a null one) as zeros
    out.clear();
    return length == 0 && object == 0;
  }
  const Collection* c = collection(address);
  if (!c || object == 0 || object >= c->objects.size()) return false;
  const auto [at, size] = c->objects[object];
  if (size != length || at == 0) return false;
  out.assign(reinterpret_cast<const char*>(c->bytes.data() + at), size);
  return true;
}

const GlobalHeapText::Collection* GlobalHeapText::collection(std::uint64_t address) {
  if (const auto it = index_.find(address); it != index_.end()) {
    cache_.splice(cache_.begin(), cache_, it->second);
    return &*it->second;
  }
  Collection c;
  if (!load(address, c)) return nullptr;
  cached_bytes_ += c.bytes.size();
  cache_.push_front(std::move(c));
  index_[address] = cache_.begin();
  while (cached_bytes_ > cache_bound && cache_.size() > 1) {
    cached_bytes_ -= cache_.back().bytes.size();
    index_.erase(cache_.back().address);
    cache_.pop_back();
  }
  return &cache_.front();
}

// The collection's layout (format version 1): "GCOL", version 1, 3 reserved
// bytes, its size (8 bytes, header included); then objects, each an index
// (2 bytes), a reference count (2), 4 reserved bytes, its size (8) and its
// bytes padded to a multiple of 8; index 0 is the free space, the last.
bool GlobalHeapText::load(std::uint64_t address, Collection& c) const {
  unsigned char head[16];
  if (!read_file_bytes(file_, base_ + address, sizeof head, head)) return false;
  if (std::memcmp(head, "GCOL", 4) != 0 || head[4] != 1) return false;
  const std::uint64_t size = le(head + 8, 8);
  if (size < sizeof head || size > largest_collection) return false;
  c.address = address;
  c.bytes.resize(std::size_t(size));
  if (!read_file_bytes(file_, base_ + address, c.bytes.size(), c.bytes.data())) return false;
  for (std::size_t at = sizeof head; at + 16 <= c.bytes.size();) {
    const unsigned char* o = c.bytes.data() + at;
    const std::uint64_t index = le(o, 2), bytes = le(o + 8, 8);
    if (index == 0) break;
    if (bytes > c.bytes.size() - at - 16) return false;
    if (index >= c.objects.size()) c.objects.resize(std::size_t(index) + 1, {0, 0});
    c.objects[std::size_t(index)] = {at + 16, std::size_t(bytes)};
    at += 16 + (std::size_t(bytes) + 7) / 8 * 8;
  }
  return true;
}

}  // namespace chaosweep

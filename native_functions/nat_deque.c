// The deque natives (language.md §13.2): double-ended queues stored in an
// ordinary array, whose layout programs can see, so it is upstream's:
//
//   Q[0] = n, the number of stored words     Q[1] = j, where the ring starts
//   Q[2 ... K+1] = the ring of capacity K    (K = length of Q - 2)
//
// The word at logical position p is Q[2 + (j + p) mod K]; a zero-filled
// array is an empty deque. `src`/`dest` arguments move their whole size at
// once. Errors carry the full payload (pc, length of Q, offending index or
// size), where upstream sends only the pc (bytecode.md §8.1).
//
// The header is program data: a deque whose n or j is out of range (never
// made by these functions) is refused with the same error, since upstream
// would write outside the array. The module, at the end, lists the natives
// in their standard order.

#include <stddef.h>

#include "nat_internal.h"
#include "nat_words.h"

#define DEQUE_COUNT        0 // Q[0]
#define DEQUE_START        1 // Q[1]
#define DEQUE_HEADER_WORDS 2 // the ring follows the header

typedef struct deque {
    int16_t *words;    // the whole array Q
    uint16_t length;   // of Q, for error reports
    uint16_t capacity; // K
    uint16_t count;    // n, 0 ... K
    uint16_t start;    // j, 0 ... K-1 (0 when K = 0)
} deque;

// Fetches the deque at `address` of `length_word` words and checks its
// header. Returns false, the VM stopped, when it is unusable.
static bool open_deque(vm_state *vm, int16_t address, int16_t length_word, deque *queue)
{
    uint16_t length = nat_length(length_word);
    queue->words = vm_variables(vm, (uint16_t)address, length);
    if (queue->words == NULL)
        return false;
    queue->length = length;
    if (length < DEQUE_HEADER_WORDS) {
        vm_error_array_access(vm, length, length);
        return false;
    }
    queue->capacity = length - DEQUE_HEADER_WORDS;
    int16_t count = queue->words[DEQUE_COUNT];
    int16_t start = queue->words[DEQUE_START];
    if (count < 0 || (uint16_t)count > queue->capacity) {
        vm_error_array_access(vm, length, (uint16_t)count);
        return false;
    }
    if (start < 0 || (start > 0 && (uint16_t)start >= queue->capacity)) {
        vm_error_array_access(vm, length, (uint16_t)start);
        return false;
    }
    queue->count = (uint16_t)count;
    queue->start = (uint16_t)start;
    return true;
}

// Ring slot `offset` slots after slot `slot`, for slot < K and offset <= K
// (so K - size slots after is size slots before), with no sum that could
// overflow 16 bits.
static uint16_t forward(const deque *queue, uint16_t slot, uint16_t offset)
{
    uint16_t room = queue->capacity - slot;
    return offset >= room ? offset - room : slot + offset;
}

static int16_t *ring(const deque *queue)
{
    return queue->words + DEQUE_HEADER_WORDS;
}

static void store_header(const deque *queue)
{
    queue->words[DEQUE_START] = (int16_t)queue->start;
    queue->words[DEQUE_COUNT] = (int16_t)queue->count;
}

// Error unless 0 <= index <= K - 1 (deque.get, set, insert and erase).
static bool check_index(vm_state *vm, const deque *queue, int16_t index)
{
    if (index < 0 || (uint16_t)index >= queue->capacity) {
        vm_error_array_access(vm, queue->length, (uint16_t)index);
        return false;
    }
    return true;
}

// Error unless the `size` words from logical position `index` are stored
// (index + size <= n); the report names index + size, their end.
static bool check_stored(vm_state *vm, const deque *queue, uint16_t index, uint16_t size)
{
    if (size > queue->count || index > queue->count - size) {
        vm_error_array_access(vm, queue->length, (uint16_t)(index + size));
        return false;
    }
    return true;
}

// Error unless `size` more words fit (deque.insert and push).
static bool check_room(vm_state *vm, const deque *queue, uint16_t size)
{
    if (size > queue->capacity - queue->count) {
        vm_error_array_access(vm, queue->length, (uint16_t)(queue->count + size));
        return false;
    }
    return true;
}

// Copies `count` words one by one from logical position `from` to logical
// position `to` (both <= K), going up, or down when `descending`; the
// direction decides what overlapping moves do, so it is upstream's.
static void move_words(const deque *queue,
                       uint16_t to,
                       uint16_t from,
                       uint16_t count,
                       bool descending)
{
    if (count == 0)
        return;
    int16_t *words = ring(queue);
    uint16_t to_slot = forward(queue, queue->start, to);
    uint16_t from_slot = forward(queue, queue->start, from);
    // One slot back is K - 1 slots forward.
    uint16_t step = descending ? queue->capacity - 1 : 1;
    for (; count > 0; --count) {
        words[to_slot] = words[from_slot];
        to_slot = forward(queue, to_slot, step);
        from_slot = forward(queue, from_slot, step);
    }
}

// Copies `size` words between `tuple` and the ring from logical position
// `index` on: into the ring when `into_ring`, out of it otherwise.
static void copy_words(const deque *queue,
                       uint16_t index,
                       int16_t *tuple,
                       uint16_t size,
                       bool into_ring)
{
    int16_t *words = ring(queue);
    uint16_t slot = forward(queue, queue->start, index);
    for (uint16_t i = 0; i < size; ++i) {
        if (into_ring)
            words[slot] = tuple[i];
        else
            tuple[i] = words[slot];
        slot = forward(queue, slot, 1);
    }
}

// Inserts src before logical position `index` (< K; size <= K - n), moving
// whichever side of the ring is shorter, as upstream does (without its
// defect for 1 <= index < n/2, language.md §13.2).
static void insert_words(deque *queue, uint16_t index, int16_t *src, uint16_t size)
{
    if (index < queue->count / 2) {
        // Start `size` slots earlier, and move the first `index` words there.
        queue->start = forward(queue, queue->start, queue->capacity - size);
        move_words(queue, 0, size, index, false);
    } else if (index < queue->count) {
        // Move the words from `index` on `size` slots up, the last first.
        uint16_t last = queue->count - 1;
        move_words(queue, last + size, last, queue->count - index, true);
    }
    copy_words(queue, index, src, size, true);
    queue->count += size;
    store_header(queue);
}

// Removes `size` words from logical position `index` on (index + size <= n),
// moving the shorter side of the ring.
static void erase_words(deque *queue, uint16_t index, uint16_t size)
{
    // Upstream never ends for size 0 in one case; removing nothing is ours.
    if (size == 0)
        return;
    if (index < queue->count / 2) {
        // Move the first `index` words `size` slots up, the last first.
        move_words(queue, index + size - 1, index - 1, index, true);
        queue->start = forward(queue, queue->start, size);
    } else {
        // Move the words after the gap `size` slots down, the first first.
        move_words(queue, index, index + size, queue->count - size - index, false);
    }
    queue->count -= size;
    store_header(queue);
}

NATIVE(deque_size, 3, W_DEQUE "." W_SIZE, "report " W_SIZE W_OF W_DEST, P(N, W_DEQUE) P(1, W_SIZE));

static void nat_deque_size_function(vm_state *vm, const int16_t *arguments)
{
    // Only n is read, so the array needs just that word, not a whole header.
    uint16_t length = nat_size_after(arguments, 2);
    const int16_t *words = vm_variables(vm, (uint16_t)arguments[0], length);
    if (words == NULL)
        return;
    int16_t *size = vm_variables(vm, (uint16_t)arguments[1], 1);
    if (size == NULL)
        return;
    if (length < DEQUE_COUNT + 1) {
        vm_error_array_access(vm, length, DEQUE_COUNT);
        return;
    }
    *size = words[DEQUE_COUNT];
}

// The layout of deque.get, set and insert: &deque, &tuple, &index, N, M.
// Returns false, the VM stopped, when an argument is unusable.
static bool open_indexed(vm_state *vm,
                         const int16_t *arguments,
                         deque *queue,
                         int16_t **tuple,
                         uint16_t *tuple_size,
                         int16_t *index)
{
    if (!open_deque(vm, arguments[0], arguments[3], queue))
        return false;
    *tuple_size = nat_length(arguments[4]);
    *tuple = vm_variables(vm, (uint16_t)arguments[1], *tuple_size);
    if (*tuple == NULL)
        return false;
    const int16_t *index_variable = vm_variables(vm, (uint16_t)arguments[2], 1);
    if (index_variable == NULL)
        return false;
    *index = *index_variable;
    return check_index(vm, queue, *index);
}

// deque.get and deque.set: copies between the tuple and the stored words
// from index on, into the deque when `into_deque`.
static void transfer_at_index(vm_state *vm, const int16_t *arguments, bool into_deque)
{
    deque queue;
    int16_t *tuple;
    uint16_t size;
    int16_t index;
    if (!open_indexed(vm, arguments, &queue, &tuple, &size, &index))
        return;
    if (!check_stored(vm, &queue, (uint16_t)index, size))
        return;
    copy_words(&queue, (uint16_t)index, tuple, size, into_deque);
}

NATIVE(deque_get,
       5,
       W_DEQUE ".get",
       W_FILL " " W_DEST W_FROM W_DEQUE " at " W_INDEX,
       P(N, W_DEQUE) P(M, W_DEST) P(1, W_INDEX));

static void nat_deque_get_function(vm_state *vm, const int16_t *arguments)
{
    transfer_at_index(vm, arguments, false);
}

NATIVE(deque_set,
       5,
       W_DEQUE ".set",
       "copies " W_SRC W_TO W_DEQUE " at " W_INDEX,
       P(N, W_DEQUE) P(M, W_SRC) P(1, W_INDEX));

static void nat_deque_set_function(vm_state *vm, const int16_t *arguments)
{
    transfer_at_index(vm, arguments, true);
}

NATIVE(deque_insert,
       5,
       W_DEQUE "." W_INSERT,
       W_SHIFT " " W_DEQUE " at " W_INDEX W_BY "len(" W_SRC ")" W_AND W_INSERT " " W_SRC,
       P(N, W_DEQUE) P(M, W_SRC) P(1, W_INDEX));

static void nat_deque_insert_function(vm_state *vm, const int16_t *arguments)
{
    deque queue;
    int16_t *src;
    uint16_t size;
    int16_t index;
    if (!open_indexed(vm, arguments, &queue, &src, &size, &index))
        return;
    // As upstream, index may be past n (up to K - 1): it inserts into
    // words that are not stored yet.
    if (!check_room(vm, &queue, size))
        return;
    insert_words(&queue, (uint16_t)index, src, size);
}

NATIVE(deque_erase,
       4,
       W_DEQUE "." W_ERASE,
       W_SHIFT " " W_DEQUE " at " W_INDEX W_BY "len" W_TO W_ERASE,
       P(N, W_DEQUE) P(1, W_INDEX) P(1, "len"));

static void nat_deque_erase_function(vm_state *vm, const int16_t *arguments)
{
    deque queue;
    if (!open_deque(vm, arguments[0], arguments[3], &queue))
        return;
    int16_t *scalars[2];
    if (!nat_spans(vm, arguments + 1, 2, 1, scalars))
        return;
    int16_t index = *scalars[0];
    int16_t size = *scalars[1];
    if (!check_index(vm, &queue, index))
        return;
    // A negative size is refused: upstream compares it as unsigned.
    if (size < 0) {
        vm_error_array_access(vm, queue.length, (uint16_t)(index + size));
        return;
    }
    if (!check_stored(vm, &queue, (uint16_t)index, (uint16_t)size))
        return;
    erase_words(&queue, (uint16_t)index, (uint16_t)size);
}

// The layout of the push and pop functions: &deque, &tuple, N, M.
static bool open_end(vm_state *vm,
                     const int16_t *arguments,
                     deque *queue,
                     int16_t **tuple,
                     uint16_t *tuple_size)
{
    if (!open_deque(vm, arguments[0], arguments[2], queue))
        return false;
    *tuple_size = nat_length(arguments[3]);
    *tuple = vm_variables(vm, (uint16_t)arguments[1], *tuple_size);
    return *tuple != NULL;
}

// deque.push_front and push_back.
static void push(vm_state *vm, const int16_t *arguments, bool at_back)
{
    deque queue;
    int16_t *src;
    uint16_t size;
    if (!open_end(vm, arguments, &queue, &src, &size) || !check_room(vm, &queue, size))
        return;
    insert_words(&queue, at_back ? queue.count : 0, src, size);
}

// deque.pop_front and pop_back.
static void pop(vm_state *vm, const int16_t *arguments, bool at_back)
{
    deque queue;
    int16_t *dest;
    uint16_t size;
    if (!open_end(vm, arguments, &queue, &dest, &size) || !check_stored(vm, &queue, 0, size))
        return;
    uint16_t index = at_back ? queue.count - size : 0;
    copy_words(&queue, index, dest, size, false);
    erase_words(&queue, index, size);
}

NATIVE(deque_push_front,
       4,
       W_DEQUE ".push_" W_FRONT,
       W_INSERT " " W_SRC " before" W_THE W_FRONT W_OF W_DEQUE,
       P(N, W_DEQUE) P(M, W_SRC));

static void nat_deque_push_front_function(vm_state *vm, const int16_t *arguments)
{
    push(vm, arguments, false);
}

NATIVE(deque_push_back,
       4,
       W_DEQUE ".push_" W_BACK,
       W_INSERT " " W_SRC " after" W_THE W_BACK W_OF W_DEQUE,
       P(N, W_DEQUE) P(M, W_SRC));

static void nat_deque_push_back_function(vm_state *vm, const int16_t *arguments)
{
    push(vm, arguments, true);
}

NATIVE(deque_pop_front,
       4,
       W_DEQUE ".pop_" W_FRONT,
       W_FILL " " W_DEST W_FROM W_FRONT W_OF W_DEQUE " then " W_ERASE W_ELEMENT "s",
       P(N, W_DEQUE) P(M, W_DEST));

static void nat_deque_pop_front_function(vm_state *vm, const int16_t *arguments)
{
    pop(vm, arguments, false);
}

NATIVE(deque_pop_back,
       4,
       W_DEQUE ".pop_" W_BACK,
       W_FILL " " W_DEST W_FROM W_BACK W_OF W_DEQUE " then " W_ERASE W_ELEMENT "s",
       P(N, W_DEQUE) P(M, W_DEST));

static void nat_deque_pop_back_function(vm_state *vm, const int16_t *arguments)
{
    pop(vm, arguments, true);
}

static const vm_native deque_natives[] = {
    NAT_RECORD(deque_size),      NAT_RECORD(deque_get),       NAT_RECORD(deque_set),
    NAT_RECORD(deque_insert),    NAT_RECORD(deque_erase),     NAT_RECORD(deque_push_front),
    NAT_RECORD(deque_push_back), NAT_RECORD(deque_pop_front), NAT_RECORD(deque_pop_back),
};

const vm_native_module nat_deque_module = NAT_MODULE(deque_natives);

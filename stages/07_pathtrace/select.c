/*
 * select.c - quickselect (Hoare's FIND, CACM 4(7), 1961) over the BVH
 * build's records: median-of-three pivots, a branch-free three-way
 * partition, insertion sort for short ranges.
 */
#include "select.h"

#include <stdbool.h>
#include <string.h>

/* Ranges at most this long are finished by insertion sort. */
#define SELECT_SMALL 16

/* Whole 16-byte copies: assigned field by field, a record that the
 * partition reads back 16 bytes at once would wait for its pieces to reach
 * memory (a failed store forwarding: it halved the build's speed). */
static void
swap_refs(struct build_ref *a, struct build_ref *b)
{
    struct build_ref tmp;
    memcpy(&tmp, a, sizeof tmp);
    memcpy(a, b, sizeof tmp);
    memcpy(b, &tmp, sizeof tmp);
}

/* Order refs[lo], refs[mid], refs[hi] by key and return the middle key: a
 * pivot that is not the range's extreme unless keys repeat. */
static float
median_of_three(struct build_ref *refs, int lo, int hi, int axis)
{
    int mid = lo + (hi - lo) / 2;
    if (refs[mid].centroid[axis] < refs[lo].centroid[axis]) {
        swap_refs(&refs[mid], &refs[lo]);
    }
    if (refs[hi].centroid[axis] < refs[lo].centroid[axis]) {
        swap_refs(&refs[hi], &refs[lo]);
    }
    if (refs[hi].centroid[axis] < refs[mid].centroid[axis]) {
        swap_refs(&refs[hi], &refs[mid]);
    }
    return refs[mid].centroid[axis];
}

/*
 * Move the refs of refs[lo, hi] whose key is below the pivot (or equal to
 * it, when or_equal) to the front; returns where the others start.  Lomuto's
 * partition written without a branch on the key: every element is swapped
 * and the boundary moves by 0 or 1.  On random keys a branch would be
 * mispredicted half the time, which costs more than the whole loop body.
 */
static int
partition(struct build_ref *refs, int lo, int hi, int axis, float pivot, bool or_equal)
{
    int j = lo;
    for (int i = lo; i <= hi; i++) {
        float key = refs[i].centroid[axis];
        int goes_first = (key < pivot) | (or_equal & (key == pivot)); /* | and &: no branch */
        swap_refs(&refs[i], &refs[j]);
        j += goes_first;
    }
    return j;
}

static void
insertion_sort(struct build_ref *refs, int lo, int hi, int axis)
{
    for (int i = lo + 1; i <= hi; i++) {
        struct build_ref r = refs[i];
        int j = i;
        for (; j > lo && refs[j - 1].centroid[axis] > r.centroid[axis]; j--) {
            refs[j] = refs[j - 1];
        }
        refs[j] = r;
    }
}

/*
 * Rearrange refs[0, n) so that refs[k] is the element a sort by
 * centroid[axis] would put there, none before it greater and none after it
 * smaller: quickselect (Hoare's FIND, CACM 4(7), 1961), expected O(n).  Each
 * round splits the range into keys below the pivot, equal to it and above it
 * (the second pass only when k is not below), and keeps the part holding k.
 * The equal part is never empty, so every round shrinks the range, even
 * when all the keys are equal (all centroids coincide).
 */
void
select_kth(struct build_ref *refs, int n, int k, int axis)
{
    int lo = 0;
    int hi = n - 1;
    while (hi - lo > SELECT_SMALL) {
        float pivot = median_of_three(refs, lo, hi, axis);
        int equal = partition(refs, lo, hi, axis, pivot, false);
        if (k < equal) {
            hi = equal - 1;
            continue;
        }
        int above = partition(refs, equal, hi, axis, pivot, true);
        if (k < above) {
            return;
        }
        lo = above;
    }
    insertion_sort(refs, lo, hi, axis);
}

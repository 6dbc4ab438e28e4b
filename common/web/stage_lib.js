// stage_lib.js - the JavaScript side of web_main.c's web_post_pass, linked
// into every stage's module (emcc --js-library): the worker that runs the
// module sets Module.onPass, which gets a copy of the pass's image.
mergeInto(LibraryManager.library, {
    web_post_pass: function (rgb, width, height, passes) {
        var first = rgb >> 2;
        var floats = HEAPF32.slice(first, first + width * height * 3);
        Module.onPass(floats, width, height, passes);
    },
});

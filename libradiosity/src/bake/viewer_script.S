/* The bundled viewer script (web/viewer/main.js with three.js), as bytes in read-only data:
   RADIOSITY_VIEWER_SCRIPT names the bundle, or is empty when the build had none. */
    .section .rodata
    .global radiosity_viewer_script
    .global radiosity_viewer_script_end
radiosity_viewer_script:
#ifdef RADIOSITY_VIEWER_SCRIPT
    .incbin RADIOSITY_VIEWER_SCRIPT
#endif
radiosity_viewer_script_end:
    .byte 0
    .section .note.GNU-stack,"",@progbits

"""A worked example for backend authors: the Blinkenboard, an imaginary board.

Read ``docs/testing-backends.rst`` alongside it. The Blinkenboard has four LEDs and a
button, and speaks a tiny line protocol at 115200 baud:

===============  =======================  ==========================================
host sends       board answers            meaning
===============  =======================  ==========================================
``?``            ``BLINKEN:<version>``    who are you? (the handshake)
``L<n><0|1>``    ``OK``                   light (1) or darken (0) LED ``n`` (0 to 3)
``B``            ``B0`` or ``B1``         is the button held?
anything else    ``ERR <reason>``         the board did not understand
===============  =======================  ==========================================

Every line ends with ``\\n``.

* :mod:`.blinkenboard`: the Board class, what students use;
* :mod:`.blinken_backend`: the hardware backend, over a serial link;
* :mod:`.blinken_simulator`: a simulator of the board, byte for byte.
"""

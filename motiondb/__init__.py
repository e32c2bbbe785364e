"""motiondb stage."""
